#pragma once
/// @file atlas_view.h
/// Shows one atlas image with its regions drawn over it (QGraphicsView, one rectangle per region
/// with a resize handle at its bottom-right corner). Left drag on a region moves it, on its
/// handle resizes it; the view only reports the edits (regionEdited, one merge key per drag) and
/// the panel turns them into undo commands. Isolating R, G, B or A shows that channel as grey.

#include "core/image.h"
#include "core/texture_ref.h"

#include <QGraphicsView>
#include <QPointF>
#include <vector>

class QGraphicsPixmapItem;
class QGraphicsRectItem;

namespace velvet::ui {

class AtlasView : public QGraphicsView {
    Q_OBJECT
public:
    /// -1: all channels; 0..3: R, G, B, A alone.
    enum Channel { AllChannels = -1, Red = 0, Green = 1, Blue = 2, Alpha = 3 };

    explicit AtlasView(QWidget* parent = nullptr);

    /// Shows @p image (linear values shown as stored, clamped to [0, 1]; albedo is sRGB-encoded
    /// as loaded) and the regions. @p srgb: the values are display-encoded already.
    void setAtlas(const Image& image, const std::vector<AtlasRegion>& regions);
    void setChannel(int channel);
    int channel() const { return m_channel; }
    void setSelectedRegion(int index);
    int selectedRegion() const { return m_selected; }
    /// The displayed image (after channel isolation), for tests.
    QImage displayedImage() const { return m_displayed; }
    /// View coordinates of an atlas texel position (tests drive drags with these).
    QPoint viewPosition(QPointF atlasTexel) const;
    /// Half the handle's size, in view pixels.
    static constexpr int kHandleRadius = 6;

signals:
    void regionSelected(int index);
    /// A drag moved / resized region @p index to @p region; one @p mergeKey per drag.
    void regionEdited(int index, velvet::AtlasRegion region, int mergeKey);

protected:
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;

private:
    enum class Drag { None, Move, Resize };
    void refreshImage();
    void rebuildRegions();
    void fit();

    Image m_image;
    QImage m_displayed;
    std::vector<AtlasRegion> m_regions;
    int m_channel = AllChannels;
    int m_selected = -1;
    QGraphicsPixmapItem* m_pixmap;
    std::vector<QGraphicsRectItem*> m_items;
    Drag m_drag = Drag::None;
    QPointF m_dragStart;
    AtlasRegion m_startRegion;
    int m_mergeKey = 0;
};

} // namespace velvet::ui
