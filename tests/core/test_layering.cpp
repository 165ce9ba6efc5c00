// Proves the layers keep to DESIGN.md: core/ knows no GL and no Qt GUI, render/ knows no Qt, and
// no public header leaks a heavy third-party library. Scans the source tree as text, so a stray
// include fails here with its file and line before it becomes a link-time tangle.
#include <QtTest>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Rule {
    std::string folder;   ///< top-level folder the rule applies to
    bool headersOnly;     ///< only .h files
    std::regex forbidden; ///< matched against the included name
    std::string why;
};

std::vector<std::string> violations(const std::vector<Rule>& rules) {
    const fs::path root = VELVET_SOURCE_DIR;
    // Plain string literals, not raw ones: moc misreads quotes inside raw strings.
    const std::regex include("^\\s*#\\s*include\\s*[<\"]([^>\"]+)[>\"]");
    std::vector<std::string> found;
    for (const Rule& rule : rules) {
        const fs::path folder = root / rule.folder;
        if (!fs::exists(folder))
            continue;
        for (const auto& entry : fs::recursive_directory_iterator(folder)) {
            const std::string ext = entry.path().extension().string();
            const bool header = ext == ".h" || ext == ".hpp";
            if (!entry.is_regular_file() || !(header || ext == ".cpp" || ext == ".cc"))
                continue;
            if (rule.headersOnly && !header)
                continue;
            std::ifstream in(entry.path());
            std::string line;
            for (int n = 1; std::getline(in, line); ++n) {
                std::smatch m;
                if (std::regex_search(line, m, include) &&
                    std::regex_search(m[1].str(), rule.forbidden))
                    found.push_back(fs::relative(entry.path(), root).string() + ":" +
                                    std::to_string(n) + ": includes <" + m[1].str() + "> (" +
                                    rule.why + ")");
            }
        }
    }
    return found;
}

void expectNone(const std::vector<Rule>& rules) {
    const auto found = violations(rules);
    for (const std::string& v : found)
        qWarning().noquote() << QString::fromStdString(v);
    QVERIFY2(found.empty(), "layering violations above");
}

} // namespace

class TestLayering : public QObject {
    Q_OBJECT
private slots:
    void coreHasNoGlAndNoQtGui() {
        expectNone(
            {{"core", false,
              std::regex("^(GL|GLES[0-9]*|EGL|KHR|epoxy)/|^Qt(Gui|Widgets|OpenGL|OpenGLWidgets)/|"
                         "^QOpenGL|^QWidget|^QImage|^QPixmap|^QPainter|^QColor$|^QWindow|"
                         "^Q(Gui)?Application$|^QSurface"),
              "core/ is the model: no GL, no Qt GUI"}});
    }
    void renderHasNoQt() {
        expectNone({{"render", false, std::regex("^Qt|^Q[A-Z]"),
                     "render/ runs under bare EGL too: no Qt"}});
    }
    void headersHideHeavyLibraries() {
        const std::regex heavy("^(assimp|OpenImageIO|OpenColorIO|nlohmann)/");
        const std::string why = "third-party headers stay inside .cpp files";
        expectNone({{"core", true, heavy, why},
                    {"render", true, heavy, why},
                    {"ui", true, heavy, why},
                    {"app", true, heavy, why}});
    }
    void theScannerFindsViolations() {
        // Guards against a scanner that silently matches nothing.
        const auto found = violations({{"core", false, std::regex("^core/"), "self-check"}});
        QVERIFY(!found.empty());
        QVERIFY(found.front().find(":") != std::string::npos);
    }
};

QTEST_APPLESS_MAIN(TestLayering)
#include "test_layering.moc"
