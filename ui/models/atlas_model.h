#pragma once
/// @file atlas_model.h
/// The atlas panel's view of the document's atlases (core/atlas_document.h): the albedo, material
/// (R specular, G roughness, B metallic, the seeds' packing) and normal atlases, each a list of
/// source images with their regions, and the composed atlas image. The atlases belong to the
/// document (DocumentController::atlases): they are saved beside the scene as a `velvet.atlas`
/// file the scene names, and opened with it. Exporting writes the composed images (PNG, EXR, ...
/// through core writeImage, atomically); assigning a region to a material slot exports the atlas
/// first when it has no file.
///
/// Edits go through undo commands (ui/commands/atlas_commands.h) pushed on the document's undo
/// stack; the set* functions are what the commands apply.

#include "core/atlas_document.h"
#include "core/atlas_packing.h"
#include "core/channel_packing.h"
#include "core/image.h"
#include "core/texture_ref.h"

#include <QObject>
#include <QString>
#include <QStringList>
#include <vector>

class QUndoStack;

namespace velvet::ui {

class DocumentController;

using velvet::AtlasDocument;
using velvet::AtlasEntry;
using velvet::AtlasKind;
using velvet::kAtlasKindCount;

class AtlasModel : public QObject {
    Q_OBJECT
public:
    explicit AtlasModel(DocumentController* controller, QObject* parent = nullptr);

    static QString kindLabel(AtlasKind kind);
    /// The texture slot a region of this atlas fills by default.
    static TextureSlot defaultSlot(AtlasKind kind);

    const AtlasDocument& atlas(AtlasKind kind) const;
    QUndoStack* undoStack() const;

    /// @name Edits (one undo command each)
    /// @{
    /// Adds images and repacks the whole atlas (core planAtlas, skyline with padding). False +
    /// @p error when they do not fit (nothing changes).
    bool addImages(AtlasKind kind, std::vector<AtlasEntry> images, QString* error);
    /// Reads image files and adds them (addImages). Unreadable files are reported in @p error.
    bool addImageFiles(AtlasKind kind, const QStringList& files, QString* error);
    /// Packs the current entries again from scratch (undoable).
    bool repack(AtlasKind kind, QString* error);
    /// Moves / resizes a region (clamped into the atlas). Edits with the same non-zero
    /// @p mergeKey on the same region (one drag) merge into one command.
    void editRegion(AtlasKind kind, int index, AtlasRegion region, int mergeKey = 0);
    /// @}

    /// @name Applied by commands
    /// @{
    void setAtlas(AtlasKind kind, AtlasDocument atlas);
    void setRegion(AtlasKind kind, int index, AtlasRegion region);
    /// @}

    /// Writes the composed atlas to @p path (format by extension; EXR as half, PNG 8 bit for
    /// albedo and 16 bit otherwise). Atomic. Remembers the path.
    bool exportAtlas(AtlasKind kind, const QString& path, QString* error);
    /// Writes every non-empty atlas to @p folder as "<stem>-albedo.<ext>", "<stem>-material.<ext>"
    /// and "<stem>-normal.<ext>" (core exportAtlasImages, atomic). @p written gets the paths.
    bool exportAll(const QString& folder, const QString& stem, const QString& extension,
                   QStringList* written, QString* error);
    /// Writes the material atlas (R specular, G roughness, B metallic, the seeds' packing)
    /// repacked into an engine's layout (core/channel_packing.h: glTF metallic-roughness, Unreal
    /// ORM, Unity HDRP mask map), 16-bit PNG or half EXR by extension, atomically. Maps the atlas
    /// does not hold (occlusion, detail mask) get the layout's neutral value.
    bool exportMaterialAtlasPacked(PackLayout layout, const QString& path, QString* error);
    /// The atlas's file, exporting it first to the user data folder (atlases/) when it has none
    /// yet. Empty + @p error on failure.
    QString ensureFile(AtlasKind kind, QString* error);

    /// Composes @p atlas.image from its entries (core composeAtlas).
    static void compose(AtlasDocument& atlas) { composeAtlas(atlas); }
    /// A merge key no other region gesture used.
    static int nextMergeKey();

signals:
    /// The atlas's entries, regions or image changed (an edit, undo, redo, open, new).
    void atlasChanged(velvet::AtlasKind kind);

private:
    bool pack(AtlasDocument& atlas, QString* error) const;

    DocumentController* m_controller;
};

} // namespace velvet::ui
