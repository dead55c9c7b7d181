#include "trac0r/material.h"

namespace trac0r {

const char* to_string(MaterialType type) {
    switch (type) {
    case MaterialType::emissive:
        return "emissive";
    case MaterialType::diffuse:
        return "diffuse";
    case MaterialType::glass:
        return "glass";
    case MaterialType::glossy:
        return "glossy";
    }
    return "unknown";
}

}  // namespace trac0r
