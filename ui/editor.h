#pragma once
/// @file editor.h
/// Entry point of the editor GUI.

#include <string>

namespace velvet::ui {

struct EditorOptions {
    std::string openFile;       ///< a scene or material preset to open; empty: the default scene
    std::string screenshotFile; ///< non-empty: save the window after the first frame, then exit
};

/// Creates the QApplication and main window and runs the event loop. Returns the exit code
/// (0, or 3 when no OpenGL 4.5 context could be made / the screenshot failed).
int runEditor(int& argc, char** argv, const EditorOptions& options);

} // namespace velvet::ui
