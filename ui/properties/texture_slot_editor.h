#pragma once
/// @file texture_slot_editor.h
/// One texture slot of the material on the Properties page (issue 5): a 64 px thumbnail, the
/// file name (tooltip: full path, colour space, region), Browse…, Clear, the input colour space,
/// and drops of an image file onto the row. Every change is one SetTextureCommand pushed through
/// DocumentController::editTexture(); refresh() shows the document's value again (undo, redo,
/// open) without creating commands.
///
/// Thumbnails are read through core's readImage() on the global thread pool and cached by file
/// (path, size, modification time), colour space and region, so the panel never waits for a
/// decode. Colour slots show display-encoded sRGB (the file converted to scene-linear from its
/// input colour space, then encoded); data slots show the stored values.
///
/// Widget names: the row "textureSlot:<id>" (id as in textureSlotMetas(), e.g. "baseColor"), and
/// its children "textureSlot:<id>/thumbnail", "/file", "/browse", "/clear", "/colorSpace", and
/// the UV transform's (uv_transform_editor.h).

#include "core/texture_ref.h"

#include <QImage>
#include <QStringList>
#include <QWidget>
#include <cstdint>
#include <memory>

class QComboBox;
class QLabel;
class QToolButton;

namespace velvet {
class ColorManagement;
}

namespace velvet::ui {

class DocumentController;
class UvTransformEditor;

class TextureSlotEditor : public QWidget {
    Q_OBJECT
public:
    TextureSlotEditor(DocumentController* controller, TextureSlot slot, QWidget* parent = nullptr);
    ~TextureSlotEditor() override;

    TextureSlot slot() const { return m_slot; }
    /// The thumbnail shown (null while the slot is empty, loading, or its file is unreadable).
    QImage thumbnail() const { return m_thumbnail; }
    /// True while a thumbnail is being read in the background.
    bool thumbnailPending() const { return m_pending; }

    /// The colour spaces offered (and the conversions of the thumbnails); null: the default
    /// config is loaded once on first use.
    void setColorManagement(std::shared_ptr<const ColorManagement> colorManagement);
    /// Shows the document's value of the slot (no command). Cheap when nothing changed.
    void refresh();
    /// Fills the slot with @p path (one undo command). Refuses, with message() and no change,
    /// a file that is not an image (by extension) or whose header cannot be read.
    bool assignFile(const QString& path);
    /// Empties the slot (one undo command).
    void clearSlot();

    /// Lower-case file extensions of the image formats OpenImageIO reads.
    static const QStringList& imageExtensions();
    static bool hasImageExtension(const QString& path);
    /// "Images (*.png *.jpg …)" for file dialogs.
    static QString imageFileFilter();

signals:
    /// A refused drop or file (for the Log and the status bar).
    void message(const QString& text);
    /// A thumbnail finished loading (or was cleared).
    void thumbnailChanged();

protected:
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dragMoveEvent(QDragMoveEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void browse();
    void onColorSpaceActivated(int index);
    void fillColorSpaces();
    void requestThumbnail();
    void setThumbnail(const QImage& image, bool failed, const QString& error);
    std::shared_ptr<const ColorManagement> colorManagement();
    QString label() const;
    /// The input colour space an empty TextureRef::colorSpace means for this slot.
    QString defaultColorSpace() const;

    DocumentController* m_controller;
    TextureSlot m_slot;
    bool m_isColor;
    std::shared_ptr<const ColorManagement> m_colorManagement;
    QLabel* m_thumbLabel;
    QLabel* m_fileLabel;
    QToolButton* m_browse;
    QToolButton* m_clear;
    QComboBox* m_colorSpace;
    UvTransformEditor* m_uv;
    TextureRef m_shown;        ///< the value the row shows
    bool m_shownValid = false; ///< false until the first refresh
    QImage m_thumbnail;
    QString m_thumbnailError;
    bool m_pending = false;
    std::uint64_t m_request = 0; ///< the latest thumbnail request (older results are dropped)
};

} // namespace velvet::ui
