#include "trac0r/render_options.h"

#include "trac0r/enum_names.h"

namespace trac0r {

namespace {

const EnumName<Accel> accel_names[] = {
    {Accel::flat, "flat"}, {Accel::bvh, "bvh"}, {Accel::automatic, "auto"}};
const EnumName<Integrator> integrator_names[] = {
    {Integrator::naive, "naive"}, {Integrator::nee, "nee"}, {Integrator::bdpt, "bdpt"}};
const EnumName<LightSampler> light_sampler_names[] = {{LightSampler::power, "power"},
                                                      {LightSampler::tree, "tree"},
                                                      {LightSampler::automatic, "auto"}};
const EnumName<SamplerKind> sampler_names[] = {{SamplerKind::random, "random"},
                                               {SamplerKind::sobol, "sobol"}};

}  // namespace

Accel parse_accel(const std::string& name) {
    return enum_value(accel_names, name, "acceleration structure");
}

const char* to_string(Accel accel) { return enum_name(accel_names, accel, "auto"); }

Integrator parse_integrator(const std::string& name) {
    return enum_value(integrator_names, name, "integrator");
}

const char* to_string(Integrator integrator) {
    return enum_name(integrator_names, integrator, "naive");
}

LightSampler parse_light_sampler(const std::string& name) {
    return enum_value(light_sampler_names, name, "light sampler");
}

const char* to_string(LightSampler sampler) {
    return enum_name(light_sampler_names, sampler, "auto");
}

SamplerKind parse_sampler(const std::string& name) {
    return enum_value(sampler_names, name, "sampler");
}

const char* to_string(SamplerKind sampler) { return enum_name(sampler_names, sampler, "random"); }

}  // namespace trac0r
