/// @file fuzz_documents.cpp
/// libFuzzer entry points for the JSON documents Velvet owns: one executable per document kind,
/// chosen at compile time by VELVET_FUZZ_KIND (tests/fuzz/CMakeLists.txt), so each target's
/// corpus and coverage stay its own. Every input must be refused with problems or accepted;
/// a crash, a hang, a sanitizer report or an accepted document that does not survive its own
/// writer is a finding (docs/reliability.md, "Fuzzed parsers").

#include "core/atlas_document.h"
#include "core/document_io.h"
#include "core/post_chain_io.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace {

// Relative file references resolve inside a folder that does not exist, so a fuzzed document
// never reads the tree it was started in.
const std::filesystem::path kNoSuchFolder = "/nonexistent/velvet-fuzz";

// An accepted document must be written and read back without a problem: the writer and the
// reader agree on every value the reader lets in.
template <typename Parse, typename Write>
void checkRoundTrip(std::string_view text, Parse parse, Write write) {
    velvet::Problems problems;
    const auto first = parse(text, problems);
    if (!first)
        return;
    const std::string written = write(*first);
    velvet::Problems again;
    if (!parse(written, again))
        std::abort();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    using namespace velvet;
#if VELVET_FUZZ_KIND == 1
    checkRoundTrip(
        text,
        [](std::string_view t, Problems& p) {
            return parseMaterial(t, "fuzz.json", kNoSuchFolder, p);
        },
        [](const Material& m) { return materialToJson(m, kNoSuchFolder); });
#elif VELVET_FUZZ_KIND == 2
    checkRoundTrip(
        text,
        [](std::string_view t, Problems& p) {
            return parseScene(t, "fuzz.json", kNoSuchFolder, p);
        },
        [](const Scene& s) { return sceneToJson(s, kNoSuchFolder); });
#elif VELVET_FUZZ_KIND == 3
    checkRoundTrip(
        text, [](std::string_view t, Problems& p) { return parsePostChain(t, "fuzz.json", p); },
        [](const PostChainPreset& c) { return postChainToJson(c); });
#elif VELVET_FUZZ_KIND == 4
    checkRoundTrip(
        text,
        [](std::string_view t, Problems& p) {
            return parseAtlasSet(t, "fuzz.json", kNoSuchFolder, p);
        },
        [](const AtlasSet& a) { return atlasSetToJson(a, kNoSuchFolder); });
#else
#error "VELVET_FUZZ_KIND must be 1 (material), 2 (scene), 3 (post chain) or 4 (atlas)"
#endif
    return 0;
}
