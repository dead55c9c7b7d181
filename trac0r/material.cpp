#include "trac0r/material.h"

#include "trac0r/enum_names.h"
#include "trac0r/kernel/scatter.h"
#include "trac0r/kernel/types.h"

#include <cmath>

namespace trac0r {

static_assert(static_cast<unsigned>(MaterialType::emissive) == T0_MATERIAL_EMISSIVE &&
                  static_cast<unsigned>(MaterialType::diffuse) == T0_MATERIAL_DIFFUSE &&
                  static_cast<unsigned>(MaterialType::glass) == T0_MATERIAL_GLASS &&
                  static_cast<unsigned>(MaterialType::glossy) == T0_MATERIAL_GLOSSY &&
                  static_cast<unsigned>(MaterialType::conductor) == T0_MATERIAL_CONDUCTOR &&
                  static_cast<unsigned>(MaterialType::plastic) == T0_MATERIAL_PLASTIC &&
                  static_cast<unsigned>(MaterialType::principled) == T0_MATERIAL_PRINCIPLED,
              "MaterialType's values are the kernel's T0_MATERIAL_*");

namespace {

// The scene format's names, in the enum's order.
const EnumName<MaterialType> material_type_table[] = {{MaterialType::emissive, "emissive"},
                                                      {MaterialType::diffuse, "diffuse"},
                                                      {MaterialType::glass, "glass"},
                                                      {MaterialType::glossy, "glossy"},
                                                      {MaterialType::conductor, "conductor"},
                                                      {MaterialType::plastic, "plastic"},
                                                      {MaterialType::principled, "principled"}};

// Mitsuba 3's RGB values of its measured spectra (data/ior/*.spd, as its
// scalar_rgb variant loads them), so that a named metal looks the same in
// both renderers.
const Metal metals[] = {
    {"gold", {0.143036f, 0.375307f, 1.44205f}, {3.983f, 2.38556f, 1.60336f}},
    {"silver", {0.155276f, 0.116728f, 0.138388f}, {4.82835f, 3.12222f, 2.1469f}},
    {"copper", {0.201005f, 0.92375f, 1.10222f}, {3.91326f, 2.45305f, 2.14209f}},
    {"aluminium", {1.6575f, 0.880405f, 0.521244f}, {9.22381f, 6.2695f, 4.837f}},
    {"chromium", {4.36967f, 2.91651f, 1.6549f}, {5.20655f, 4.23131f, 3.7547f}},
    {"tungsten", {4.37082f, 3.30025f, 2.99841f}, {3.50064f, 2.60487f, 2.27323f}},
};

}  // namespace

const char* to_string(MaterialType type) { return enum_name(material_type_table, type, "unknown"); }

std::vector<std::string> material_type_names() { return enum_names(material_type_table); }

MaterialType parse_material_type(const std::string& name) {
    return enum_value(material_type_table, name, "material type");
}

const Metal* find_metal(const std::string& name) {
    for (const Metal& m : metals) {
        if (name == m.name) {
            return &m;
        }
    }
    return nullptr;
}

std::vector<std::string> metal_names() {
    std::vector<std::string> names;
    for (const Metal& m : metals) {
        names.push_back(m.name);
    }
    return names;
}

float plastic_diffuse_scale(float ior) {
    // F_dr = 2 int_0^1 F(mu) mu dmu, light inside the coat (eta_i / eta_t =
    // ior) meeting it; the midpoint rule on 4096 cells is far below float's
    // precision for this smooth integrand (but for the kink at the critical
    // angle, which costs at most one cell's width, 2.4e-4, in F_dr).
    const int cells = 4096;
    double sum = 0.0;
    for (int i = 0; i < cells; ++i) {
        const double mu = (i + 0.5) / cells;
        sum += kernel::fresnel_dielectric(static_cast<float>(mu), ior) * mu;
    }
    const double f_dr = 2.0 * sum / cells;
    return static_cast<float>(1.0 / (static_cast<double>(ior) * ior * (1.0 - f_dr)));
}

}  // namespace trac0r
