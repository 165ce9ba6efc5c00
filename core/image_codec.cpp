#include "core/image_codec.h"

#include <atomic>
#include <cstdlib>
#include <mutex>

#ifdef VELVET_IMAGE_CODEC_STATIC
extern "C" const velvet::codec::ImageCodec* velvet_image_codec();
#else
#include <dlfcn.h>
#include <unistd.h>
#endif

namespace velvet::codec {
namespace {

std::atomic<bool> g_loaded{false};

#ifndef VELVET_IMAGE_CODEC_STATIC
/// The folder of the running executable (/proc/self/exe), or empty.
std::filesystem::path executableFolder() {
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::filesystem::path() : exe.parent_path();
}

/// The module file and every place it was looked for, in order (core/image_codec.h).
std::vector<std::filesystem::path> candidates() {
    std::vector<std::filesystem::path> out;
    if (const char* file = std::getenv("VELVET_IMAGE_CODEC"); file && *file)
        out.emplace_back(file);
    if (const auto bin = executableFolder(); !bin.empty())
        out.push_back((bin / VELVET_IMAGE_CODEC_DIR / VELVET_IMAGE_CODEC_FILE).lexically_normal());
    return out;
}
#endif

struct Loaded {
    const ImageCodec* codec = nullptr;
    std::string error;
};

Loaded load() {
    Loaded result;
#ifdef VELVET_IMAGE_CODEC_STATIC
    result.codec = velvet_image_codec();
#else
    std::string tried;
    for (const auto& file : candidates()) {
        std::error_code ec;
        if (!std::filesystem::exists(file, ec)) {
            tried += (tried.empty() ? "" : ", ") + file.string() + " (missing)";
            continue;
        }
        // RTLD_LOCAL: OpenImageIO's symbols stay the module's; RTLD_NOW: a broken install fails
        // here with the loader's reason, not at a later call.
        void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            tried += (tried.empty() ? "" : ", ") + file.string() + " (" +
                     (why ? why : "cannot be loaded") + ")";
            continue;
        }
        using Entry = const ImageCodec* (*)();
        auto entry = reinterpret_cast<Entry>(dlsym(handle, "velvet_image_codec"));
        const ImageCodec* codec = entry ? entry() : nullptr;
        if (!codec || codec->abi != kImageCodecAbi) {
            tried += (tried.empty() ? "" : ", ") + file.string() +
                     " (not this build's image codec: rebuild or reinstall Velvet)";
            dlclose(handle);
            continue;
        }
        result.codec = codec; // the handle stays open for the life of the process
        break;
    }
    if (!result.codec)
        result.error = "the image codec module (" + std::string(VELVET_IMAGE_CODEC_FILE) +
                       ", OpenImageIO) is missing or broken: looked for " +
                       (tried.empty() ? std::string("it nowhere (no executable path)") : tried) +
                       "; VELVET_IMAGE_CODEC names the file";
#endif
    if (result.codec)
        g_loaded = true;
    return result;
}

} // namespace

const ImageCodec* imageCodec(std::string* error) {
    static const Loaded loaded = load(); // thread-safe once (C++11 magic statics)
    if (!loaded.codec && error)
        *error = loaded.error;
    return loaded.codec;
}

bool imageCodecLoaded() {
    return g_loaded;
}

} // namespace velvet::codec
