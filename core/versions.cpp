#include "core/versions.h"

#include <OpenColorIO/OpenColorIO.h>
#include <OpenImageIO/oiioversion.h>
#include <assimp/version.h>
#include <glm/detail/setup.hpp>
#include <nlohmann/json.hpp>

namespace velvet {

std::vector<std::pair<std::string, std::string>> dependencyVersions() {
    auto dotted = [](auto a, auto b, auto c) {
        return std::to_string(a) + "." + std::to_string(b) + "." + std::to_string(c);
    };
    return {
        {"OpenImageIO", OIIO_VERSION_STRING},
        {"OpenColorIO", OCIO_NAMESPACE::GetVersion()},
        {"Assimp", dotted(aiGetVersionMajor(), aiGetVersionMinor(), aiGetVersionPatch())},
        {"GLM", dotted(GLM_VERSION_MAJOR, GLM_VERSION_MINOR, GLM_VERSION_PATCH)},
        {"nlohmann-json", dotted(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                                 NLOHMANN_JSON_VERSION_PATCH)},
    };
}

} // namespace velvet
