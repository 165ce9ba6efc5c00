#pragma once
/// @file export_action.h
/// File > Export…: the document's material out as glTF 2.0 (.glb / .gltf), MaterialX (one filter
/// per shader node) or a Velvet preset, through core's exportMaterial — the same code as
/// `velvet export`, so the editor and the CLI write the same files (docs/interchange.md).

#include "core/texture_set_export.h"

#include <QString>
#include <QStringList>

class QWidget;

namespace velvet::ui {

class DocumentController;
class LogPanel;

/// The file-dialog filters, one per way out, in the order the dialog lists them.
QStringList exportFilters();

/// Exports the document's material to @p path with the way out @p filter names (one of
/// exportFilters(); an unknown one is taken from the path's extension). The file dialog has
/// confirmed any overwrite, so existing targets are replaced. What the format cannot carry goes
/// to @p log as warnings; a failure returns false with @p error (the file and the reason), and
/// nothing of it is left written. A texture set is baked with @p textureSet's size, file type,
/// bits and normal convention (its target is the filter's), or the CLI's defaults when null.
/// A glTF or MaterialX export bakes what the node graph drives at @p bakeSize texels square
/// (0: the CLI's default, 1024).
bool exportDocument(const DocumentController& controller, const QString& path,
                    const QString& filter, LogPanel* log, QString* error,
                    const TextureSetOptions* textureSet = nullptr, int bakeSize = 0);

/// Asks for a file (Qt's save dialog, starting in the last export folder) and, for an engine's
/// texture set, its settings (TextureSetDialog), or for a glTF or MaterialX export of a material
/// with a node graph the size its maps are baked at (remembered), and exports; errors are shown
/// in a message box and the Log. Returns whether a file was written.
bool exportDocumentInteractively(QWidget* parent, const DocumentController& controller,
                                 LogPanel* log);

} // namespace velvet::ui
