// The value rules next to the parameter metadata (core/param_meta.h).
#include "core/param_meta.h"

#include <algorithm>
#include <cmath>

namespace velvet {

glm::vec3 constrainParamValue(const ParamMeta& meta, glm::vec3 v) {
    const auto clampOne = [&](float x) {
        if (!std::isfinite(x))
            x = meta.defaultValue.x;
        return std::clamp(x, meta.min, meta.max);
    };
    switch (meta.type) {
    case ParamType::Float:
        return glm::vec3(clampOne(v.x));
    case ParamType::Color:
        return glm::vec3(clampOne(v.x), clampOne(v.y), clampOne(v.z));
    case ParamType::Choice:
        return glm::vec3(std::round(clampOne(v.x)));
    }
    return v;
}

} // namespace velvet
