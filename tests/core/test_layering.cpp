// Proves the layers keep to DESIGN.md, whose arrows app -> ui -> render -> core are the only
// allowed dependencies, in both places they can be broken:
// - the build: every target_link_libraries of the layers' CMakeLists.txt links only layers below
//   its own (core links no Velvet target, render only core, ui render and core), core links no
//   GL and no Qt GUI library and render no Qt at all;
// - the sources: no file includes a header of a layer above its own, core/ includes no GL and no
//   Qt GUI header, render/ no Qt header, and no public header leaks a heavy third-party library.
// Scans the tree as text, so a stray link or include fails here with its file and line before it
// becomes a link-time tangle.
#include <QtTest>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
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

// ---- The build's arrows: target_link_libraries in the layers' CMakeLists.txt ----

/// The layers bottom-up. The reference path tracer (reference/) stands beside render/ on core:
/// the two share a rank, so neither may link the other (the ground truth must not borrow the
/// real-time renderer's code, nor render the path tracer's).
const std::vector<std::string> kLayers = {"core", "render", "reference", "ui", "app"};

/// A layer may link only layers of a lower rank.
int layerIndex(const std::string& folder) {
    static const std::map<std::string, int> rank = {
        {"core", 0}, {"render", 1}, {"reference", 1}, {"ui", 2}, {"app", 3}};
    const auto it = rank.find(folder);
    return it == rank.end() ? -1 : it->second;
}

/// One call of a CMake command: its name (lower case), its arguments and where it starts.
struct CMakeCall {
    std::string name;
    std::vector<std::string> args;
    int line = 0;
};

/// The command calls of a CMakeLists.txt text: comments (# to the end of the line, #[[ ... ]])
/// dropped, arguments split at white space, quotes removed, nested parentheses kept together.
std::vector<CMakeCall> cmakeCalls(const std::string& text) {
    std::vector<CMakeCall> calls;
    size_t i = 0;
    int line = 1;
    const auto skipComment = [&] {
        if (text.compare(i, 3, "#[[") == 0) {
            const size_t end = text.find("]]", i);
            const size_t stop = end == std::string::npos ? text.size() : end + 2;
            line += int(std::count(text.begin() + long(i), text.begin() + long(stop), '\n'));
            i = stop;
        } else {
            while (i < text.size() && text[i] != '\n')
                ++i;
        }
    };
    while (i < text.size()) {
        const char c = text[i];
        if (c == '#') {
            skipComment();
        } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            size_t j = i;
            while (j < text.size() &&
                   (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_'))
                ++j;
            CMakeCall call;
            call.name = text.substr(i, j - i);
            std::transform(call.name.begin(), call.name.end(), call.name.begin(),
                           [](unsigned char ch) { return char(std::tolower(ch)); });
            call.line = line;
            while (j < text.size() && (text[j] == ' ' || text[j] == '\t'))
                ++j;
            i = j;
            if (i >= text.size() || text[i] != '(')
                continue;
            ++i;
            int depth = 1;
            std::string arg;
            bool quoted = false;
            const auto flush = [&] {
                if (!arg.empty())
                    call.args.push_back(arg);
                arg.clear();
            };
            while (i < text.size() && depth > 0) {
                const char ch = text[i];
                if (ch == '\n')
                    ++line;
                if (quoted) {
                    if (ch == '"')
                        quoted = false;
                    else
                        arg += ch;
                } else if (ch == '"') {
                    quoted = true;
                } else if (ch == '#') {
                    flush();
                    skipComment();
                    continue;
                } else if (ch == '(') {
                    ++depth;
                    arg += ch;
                } else if (ch == ')') {
                    if (--depth > 0)
                        arg += ch;
                } else if (std::isspace(static_cast<unsigned char>(ch))) {
                    flush();
                } else {
                    arg += ch;
                }
                ++i;
            }
            flush();
            calls.push_back(std::move(call));
        } else {
            if (c == '\n')
                ++line;
            ++i;
        }
    }
    return calls;
}

/// One CMakeLists.txt of a layer: its folder's layer and its text.
struct CMakeFile {
    std::string path; ///< shown in messages
    std::string layer;
    std::string text;
};

/// The layers' CMakeLists.txt files of the source tree (tests/ link what they test and are no
/// layer).
std::vector<CMakeFile> layerCMakeFiles() {
    const fs::path root = VELVET_SOURCE_DIR;
    std::vector<CMakeFile> files;
    for (const std::string& layer : kLayers) {
        if (!fs::exists(root / layer))
            continue;
        for (const auto& entry : fs::recursive_directory_iterator(root / layer)) {
            if (!entry.is_regular_file() || entry.path().filename() != "CMakeLists.txt")
                continue;
            std::ifstream in(entry.path());
            std::ostringstream text;
            text << in.rdbuf();
            files.push_back({fs::relative(entry.path(), root).string(), layer, text.str()});
        }
    }
    return files;
}

/// Libraries (not Velvet targets) a layer must not link, with the reason.
struct ForbiddenLibrary {
    std::string layer;
    std::regex library;
    std::string why;
};

const std::vector<ForbiddenLibrary>& forbiddenLibraries() {
    static const std::vector<ForbiddenLibrary> rules = {
        {"core", std::regex("^Qt[0-9]*::(Gui|Widgets|OpenGL|OpenGLWidgets)$|EPOXY|EGL|^OpenGL::"),
         "core/ is the model: no GL, no Qt GUI"},
        {"render", std::regex("^Qt[0-9]*::"), "render/ runs under bare EGL too: no Qt"},
        {"reference", std::regex("^Qt[0-9]*::|EPOXY|EGL|^OpenGL::"),
         "reference/ is the CPU ground truth: no GL, no Qt"},
    };
    return rules;
}

/// Every link that breaks the arrows, as "file:line: what (why)". @p files are the layers'
/// CMakeLists.txt; a target's layer is the folder of the file that adds it.
std::vector<std::string> linkViolations(const std::vector<CMakeFile>& files) {
    std::map<std::string, std::string> layerOfTarget;
    for (const CMakeFile& f : files)
        for (const CMakeCall& call : cmakeCalls(f.text))
            if ((call.name == "add_library" || call.name == "add_executable") && !call.args.empty())
                layerOfTarget[call.args[0]] = f.layer;
    std::vector<std::string> found;
    for (const CMakeFile& f : files)
        for (const CMakeCall& call : cmakeCalls(f.text)) {
            if (call.name != "target_link_libraries" || call.args.empty())
                continue;
            const std::string where = f.path + ":" + std::to_string(call.line) + ": ";
            const std::string& target = call.args[0];
            const auto own = layerOfTarget.find(target);
            const std::string layer = own != layerOfTarget.end() ? own->second : f.layer;
            for (size_t a = 1; a < call.args.size(); ++a) {
                const std::string& item = call.args[a];
                if (item == "PUBLIC" || item == "PRIVATE" || item == "INTERFACE")
                    continue;
                if (item.find("${") != std::string::npos) {
                    found.push_back(where + target + " links " + item +
                                    " (a variable hides what is linked: name the targets)");
                    continue;
                }
                if (const auto dep = layerOfTarget.find(item); dep != layerOfTarget.end()) {
                    if (layerIndex(dep->second) >= layerIndex(layer))
                        found.push_back(where + target + " (" + layer + ") links " + item + " (" +
                                        dep->second + "): the arrows are app -> ui -> render -> " +
                                        "core, each layer links only those below it");
                    continue;
                }
                for (const ForbiddenLibrary& rule : forbiddenLibraries())
                    if (rule.layer == layer && std::regex_search(item, rule.library))
                        found.push_back(where + target + " links " + item + " (" + rule.why + ")");
            }
        }
    return found;
}

/// Every "target -> linked Velvet target" arrow the files declare (for the sanity checks).
std::vector<std::string> arrows(const std::vector<CMakeFile>& files) {
    std::vector<std::string> targets, out;
    for (const CMakeFile& f : files)
        for (const CMakeCall& call : cmakeCalls(f.text))
            if ((call.name == "add_library" || call.name == "add_executable") && !call.args.empty())
                targets.push_back(call.args[0]);
    for (const CMakeFile& f : files)
        for (const CMakeCall& call : cmakeCalls(f.text))
            if (call.name == "target_link_libraries" && !call.args.empty())
                for (size_t a = 1; a < call.args.size(); ++a)
                    if (std::find(targets.begin(), targets.end(), call.args[a]) != targets.end())
                        out.push_back(call.args[0] + " -> " + call.args[a]);
    return out;
}

void expectNoLinkViolations(const std::vector<CMakeFile>& files) {
    const auto found = linkViolations(files);
    for (const std::string& v : found)
        qWarning().noquote() << QString::fromStdString(v);
    QVERIFY2(found.empty(), "layering violations above");
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
        expectNone(
            {{"core", true, heavy, why},
             {"render", true, heavy, why},
             {"ui", true, heavy, why},
             {"app", true, heavy, why},
             {"reference", true,
              std::regex("^(assimp|OpenImageIO|OpenColorIO|nlohmann|embree[0-9]*|tbb|oneapi)/"),
              why}});
    }
    // Includes follow the arrows too: no layer includes a header of a layer above it.
    void includesFollowTheArrows() {
        const std::string why = "the arrows are app -> ui -> render -> core";
        expectNone({{"core", false, std::regex("^(render|reference|ui|app)/"), why},
                    {"render", false, std::regex("^(reference|ui|app)/"), why},
                    {"reference", false, std::regex("^(render|ui|app)/"), why},
                    {"ui", false, std::regex("^app/"), why}});
    }
    // The reference path tracer is CPU only: no GL and no Qt header.
    void referenceHasNoGlAndNoQt() {
        expectNone({{"reference", false, std::regex("^(GL|GLES[0-9]*|EGL|KHR|epoxy)/|^Qt|^Q[A-Z]"),
                     "reference/ is the CPU ground truth: no GL, no Qt"}});
    }

    // The build's arrows: each layer's target links only the layers below it.
    void linksFollowTheArrows() {
        const auto files = layerCMakeFiles();
        QCOMPARE(files.size() >= kLayers.size(), true);
        expectNoLinkViolations(files);
        // The scan saw the real arrows (a parser that finds nothing would pass the check above).
        const auto found = arrows(files);
        for (const char* arrow :
             {"velvet_render -> velvet_core", "velvet_reference -> velvet_core",
              "velvet_ui -> velvet_render", "velvet -> velvet_ui", "velvet -> velvet_reference"})
            QVERIFY2(std::find(found.begin(), found.end(), arrow) != found.end(), arrow);
    }

    // Guards against a link scanner that silently accepts everything: each way of breaking the
    // arrows, written as a layer's CMakeLists.txt would, is reported with its file and line.
    void theLinkScannerFindsViolations() {
        const std::vector<CMakeFile> base = {
            {"core/CMakeLists.txt", "core", "add_library(velvet_core STATIC a.cpp)\n"},
            {"render/CMakeLists.txt", "render",
             "add_library(velvet_render STATIC b.cpp)\n"
             "target_link_libraries(velvet_render PUBLIC velvet_core PRIVATE PkgConfig::EPOXY)\n"},
            {"ui/CMakeLists.txt", "ui",
             "add_library(velvet_ui STATIC c.cpp)\n"
             "target_link_libraries(velvet_ui # the widgets\n  PUBLIC velvet_render "
             "Qt6::Widgets)\n"},
            {"reference/CMakeLists.txt", "reference",
             "add_library(velvet_reference STATIC d.cpp)\n"
             "target_link_libraries(velvet_reference PUBLIC velvet_core PRIVATE embree)\n"},
        };
        QVERIFY(linkViolations(base).empty());
        const auto withLine = [&](const std::string& layer, const std::string& extra) {
            std::vector<CMakeFile> files = base;
            for (CMakeFile& f : files)
                if (f.layer == layer)
                    f.text += "\n" + extra;
            return linkViolations(files);
        };
        const struct {
            const char* layer;
            const char* cmake;
            const char* expected;
        } cases[] = {
            {"core", "target_link_libraries(velvet_core PRIVATE velvet_render)",
             "core/CMakeLists.txt:3: velvet_core (core) links velvet_render (render)"},
            {"core", "TARGET_LINK_LIBRARIES(velvet_core\n  PUBLIC\n    velvet_ui)",
             "velvet_core (core) links velvet_ui (ui)"},
            {"render", "target_link_libraries(velvet_render PRIVATE \"velvet_ui\")",
             "velvet_render (render) links velvet_ui (ui)"},
            {"render", "target_link_libraries(velvet_render PRIVATE velvet_render)",
             "velvet_render (render) links velvet_render (render)"},
            {"core", "target_link_libraries(velvet_core PRIVATE Qt6::Gui)",
             "velvet_core links Qt6::Gui (core/ is the model"},
            {"core", "target_link_libraries(velvet_core PRIVATE PkgConfig::EPOXY)",
             "velvet_core links PkgConfig::EPOXY"},
            {"render", "target_link_libraries(velvet_render PRIVATE Qt6::Core)",
             "velvet_render links Qt6::Core (render/ runs under bare EGL"},
            {"render", "target_link_libraries(velvet_render PRIVATE velvet_reference)",
             "velvet_render (render) links velvet_reference (reference)"},
            {"reference", "target_link_libraries(velvet_reference PRIVATE velvet_render)",
             "velvet_reference (reference) links velvet_render (render)"},
            {"reference", "target_link_libraries(velvet_reference PRIVATE Qt6::Core)",
             "velvet_reference links Qt6::Core (reference/ is the CPU ground truth"},
            {"core", "target_link_libraries(velvet_core PRIVATE ${MORE})",
             "a variable hides what is linked"},
        };
        for (const auto& c : cases) {
            const auto found = withLine(c.layer, c.cmake);
            QVERIFY2(found.size() == 1, c.cmake);
            QVERIFY2(found.front().find(c.expected) != std::string::npos, found.front().c_str());
        }
        // A comment that mentions a link is not a link.
        QVERIFY(withLine("core", "# target_link_libraries(velvet_core PRIVATE velvet_render)\n"
                                 "#[[ target_link_libraries(velvet_core PRIVATE velvet_ui) ]]")
                    .empty());
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
