#pragma once
// Shared helpers of the render tests: one headless context per test process, scenes built in code.

#include "core/document_io.h"
#include "core/scene.h"
#include "render/headless_context.h"

#include <QtTest>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace velvet::test {

inline render::HeadlessContext* headlessContext(std::string* error) {
    static std::string lastError;
    static std::unique_ptr<render::HeadlessContext> ctx =
        render::HeadlessContext::create(&lastError);
    if (!ctx && error)
        *error = lastError;
    return ctx.get();
}

/// The shipped default scene (core/document_io.h), loaded exactly as `velvet render` and the editor
/// load it, so the golden image is the default scene and not a copy of it. Fails the test when the
/// default preset reports any problem.
inline Scene shippedDefaultScene() {
    Problems problems;
    Scene scene = defaultScene(&problems);
    for (const Problem& p : problems.items)
        qWarning("default scene: %s", p.toString().c_str());
    if (!problems.items.empty())
        QTest::qFail("the default scene reported problems", __FILE__, __LINE__);
    return scene;
}

/// A whole text file (shader sources the reload tests break and mend); empty when unreadable.
inline std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
inline void writeText(const std::filesystem::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << text;
}

} // namespace velvet::test
