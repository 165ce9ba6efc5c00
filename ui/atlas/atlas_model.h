#pragma once
/// @file atlas_model.h
/// The atlas panel's documents: the albedo, material (R specular, G roughness, B metallic, the
/// seeds' packing) and normal atlases, each a list of source images with their regions, and the
/// composed atlas image. The atlases live in memory (they are not part of the scene file yet);
/// exporting writes the composed image (PNG, EXR, ... through core writeImage, atomically), and
/// assigning a region to a material slot exports the atlas first when it has no file.
///
/// Edits go through undo commands (ui/commands/atlas_commands.h) pushed on the document's undo
/// stack; the set* functions are what the commands apply.

#include "core/atlas_packing.h"
#include "core/image.h"
#include "core/texture_ref.h"

#include <QObject>
#include <QString>
#include <array>
#include <vector>

class QUndoStack;

namespace velvet::ui {

enum class AtlasKind { Albedo = 0, Material = 1, Normal = 2 };
inline constexpr int kAtlasKindCount = 3;

/// One image in an atlas: its source pixels and where they lie (without the padding).
struct AtlasEntry {
    QString name;
    Image source;
    AtlasRegion region;
};

/// One atlas: entries, size, padding and the composed image.
struct AtlasDocument {
    std::vector<AtlasEntry> entries;
    int width = 0;
    int height = 0;
    int padding = 4;
    Image image;      ///< composed from the entries (empty when there are none)
    QString filePath; ///< where it was last exported (empty: never)
};

class AtlasModel : public QObject {
    Q_OBJECT
public:
    explicit AtlasModel(QUndoStack* undoStack, QObject* parent = nullptr);

    static QString kindLabel(AtlasKind kind);
    /// The texture slot a region of this atlas fills by default.
    static TextureSlot defaultSlot(AtlasKind kind);

    const AtlasDocument& atlas(AtlasKind kind) const { return m_atlases[size_t(kind)]; }
    QUndoStack* undoStack() const { return m_undoStack; }

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
    /// The atlas's file, exporting it first to the user data folder (atlases/) when it has none
    /// yet. Empty + @p error on failure.
    QString ensureFile(AtlasKind kind, QString* error);

    /// Composes @p atlas.image from its entries: each source stretched (nearest) over its
    /// region, with the padding replicated from the edge texels.
    static void compose(AtlasDocument& atlas);
    /// A merge key no other region gesture used.
    static int nextMergeKey();

signals:
    /// The atlas's entries, regions or image changed.
    void atlasChanged(velvet::ui::AtlasKind kind);

private:
    bool pack(AtlasDocument& atlas, QString* error) const;

    QUndoStack* m_undoStack;
    std::array<AtlasDocument, kAtlasKindCount> m_atlases;
};

} // namespace velvet::ui
