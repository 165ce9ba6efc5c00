#pragma once
/// @file import_action.h
/// File > Import… and drops of .gltf / .glb / .mtlx on the main window: a glTF 2.0 or
/// MaterialX material applied to the document as one undoable step, through core's
/// importMaterialFile — the same code as `velvet import` (docs/interchange.md, "Import"). A file
/// with several materials lists them to choose from (a QInputDialog named
/// "importMaterialChooser"); warnings (what could not be mapped) go to the Log; a malformed file
/// is refused with a message naming the file and the place, and the document is untouched.
/// Embedded images are written into the application's data folder
/// (imports/<file stem>_<hash of its path>/), so the document can name them.

#include <QString>
#include <QStringList>

class QWidget;

namespace velvet::ui {

class DocumentController;
class LogPanel;

/// The file-dialog filter: "glTF and MaterialX (*.gltf *.glb *.mtlx)".
QString importFilter();
/// True for the extensions importFile() reads.
bool isImportableFile(const QString& path);

/// Imports @p path into @p controller's document: material @p material (NAME or INDEX; empty: ask
/// with a list when there are several, else the only one). With @p withMesh and a glTF that
/// holds a mesh, the file also becomes the preview mesh, in the same undo step. Returns whether
/// the document changed; on failure @p error gets one line ("FILE: PLACE: MESSAGE").
bool importFile(QWidget* parent, DocumentController& controller, const QString& path, LogPanel* log,
                bool withMesh, QString* error, const QString& material = {});

/// Asks for a file (Qt's open dialog, starting in the last import folder) and imports it;
/// errors are shown in a message box and the Log.
bool importFileInteractively(QWidget* parent, DocumentController& controller, LogPanel* log);

} // namespace velvet::ui
