#include "trac0r/material.h"

#include "trac0r/enum_names.h"

namespace trac0r {

namespace {

// The scene format's names, in the enum's order.
const EnumName<MaterialType> material_type_table[] = {{MaterialType::emissive, "emissive"},
                                                      {MaterialType::diffuse, "diffuse"},
                                                      {MaterialType::glass, "glass"},
                                                      {MaterialType::glossy, "glossy"}};

}  // namespace

const char* to_string(MaterialType type) { return enum_name(material_type_table, type, "unknown"); }

std::vector<std::string> material_type_names() { return enum_names(material_type_table); }

MaterialType parse_material_type(const std::string& name) {
    return enum_value(material_type_table, name, "material type");
}

}  // namespace trac0r
