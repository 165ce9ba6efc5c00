#include "ui/atlas/atlas_view.h"

#include "ui/models/atlas_model.h"

#include <QGraphicsPixmapItem>
#include <QGraphicsRectItem>
#include <QGraphicsScene>
#include <QMouseEvent>
#include <algorithm>
#include <cmath>

namespace velvet::ui {
namespace {

int toByte(float v) {
    return std::clamp(int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)), 0, 255);
}

} // namespace

AtlasView::AtlasView(QWidget* parent) : QGraphicsView(parent), m_pixmap(new QGraphicsPixmapItem) {
    setObjectName(QStringLiteral("atlasView"));
    setScene(new QGraphicsScene(this));
    scene()->addItem(m_pixmap);
    setBackgroundBrush(QColor(48, 48, 48));
    setRenderHint(QPainter::SmoothPixmapTransform, false);
    setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    setMouseTracking(true);
}

void AtlasView::setAtlas(const Image& image, const std::vector<AtlasRegion>& regions) {
    const bool resized = image.width != m_image.width || image.height != m_image.height;
    m_image = image;
    m_regions = regions;
    if (m_selected >= int(m_regions.size()))
        m_selected = -1;
    refreshImage();
    rebuildRegions();
    if (resized)
        fit();
}

void AtlasView::setChannel(int channel) {
    m_channel = std::clamp(channel, -1, 3);
    refreshImage();
}

void AtlasView::setSelectedRegion(int index) {
    m_selected = index >= 0 && index < int(m_regions.size()) ? index : -1;
    rebuildRegions();
}

void AtlasView::refreshImage() {
    if (m_image.empty()) {
        m_displayed = QImage();
        m_pixmap->setPixmap(QPixmap());
        scene()->setSceneRect(0, 0, 1, 1);
        return;
    }
    QImage img(m_image.width, m_image.height, QImage::Format_ARGB32);
    for (int y = 0; y < m_image.height; ++y) {
        auto* line = reinterpret_cast<QRgb*>(img.scanLine(y));
        for (int x = 0; x < m_image.width; ++x) {
            const glm::vec4 c = m_image.rgba(x, y);
            if (m_channel >= 0) {
                const int v = toByte(c[m_channel]);
                line[x] = qRgb(v, v, v);
            } else {
                line[x] = qRgb(toByte(c.r), toByte(c.g), toByte(c.b));
            }
        }
    }
    m_displayed = img;
    m_pixmap->setPixmap(QPixmap::fromImage(img));
    scene()->setSceneRect(0, 0, m_image.width, m_image.height);
}

void AtlasView::rebuildRegions() {
    for (QGraphicsRectItem* item : m_items)
        delete item;
    m_items.clear();
    for (size_t i = 0; i < m_regions.size(); ++i) {
        const AtlasRegion& r = m_regions[i];
        const bool selected = int(i) == m_selected;
        QPen pen(selected ? QColor(255, 200, 40) : QColor(80, 200, 255));
        pen.setCosmetic(true);
        pen.setWidth(selected ? 2 : 1);
        auto* rect = scene()->addRect(QRectF(r.x, r.y, r.width, r.height), pen);
        rect->setZValue(1);
        m_items.push_back(rect);
        // The resize handle: a small square at the bottom-right corner, constant size on screen.
        const double s = kHandleRadius / std::max(0.01, transform().m11());
        auto* handle =
            scene()->addRect(QRectF(r.x + r.width - s, r.y + r.height - s, 2 * s, 2 * s), pen,
                             QBrush(selected ? QColor(255, 200, 40) : QColor(80, 200, 255)));
        handle->setZValue(2);
        m_items.push_back(handle);
    }
}

void AtlasView::fit() {
    if (!m_image.empty())
        fitInView(scene()->sceneRect(), Qt::KeepAspectRatio);
    rebuildRegions();
}

void AtlasView::resizeEvent(QResizeEvent* event) {
    QGraphicsView::resizeEvent(event);
    fit();
}

QPoint AtlasView::viewPosition(QPointF atlasTexel) const {
    return mapFromScene(atlasTexel);
}

void AtlasView::mousePressEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton) {
        QGraphicsView::mousePressEvent(event);
        return;
    }
    const QPointF p = mapToScene(event->position().toPoint());
    const double handle = (kHandleRadius + 2) / std::max(0.01, transform().m11());
    int hit = -1;
    Drag drag = Drag::None;
    // Topmost first: the last region drawn wins.
    for (int i = int(m_regions.size()) - 1; i >= 0 && hit < 0; --i) {
        const AtlasRegion& r = m_regions[size_t(i)];
        const QPointF corner(r.x + r.width, r.y + r.height);
        if (std::abs(p.x() - corner.x()) <= handle && std::abs(p.y() - corner.y()) <= handle) {
            hit = i;
            drag = Drag::Resize;
        } else if (QRectF(r.x, r.y, r.width, r.height).contains(p)) {
            hit = i;
            drag = Drag::Move;
        }
    }
    if (hit != m_selected) {
        setSelectedRegion(hit);
        emit regionSelected(hit);
    }
    if (hit >= 0) {
        m_drag = drag;
        m_dragStart = p;
        m_startRegion = m_regions[size_t(hit)];
        m_mergeKey = AtlasModel::nextMergeKey();
    }
    event->accept();
}

void AtlasView::mouseMoveEvent(QMouseEvent* event) {
    if (m_drag == Drag::None || m_selected < 0) {
        QGraphicsView::mouseMoveEvent(event);
        return;
    }
    const QPointF d = mapToScene(event->position().toPoint()) - m_dragStart;
    AtlasRegion r = m_startRegion;
    if (m_drag == Drag::Move) {
        r.x += int(std::lround(d.x()));
        r.y += int(std::lround(d.y()));
    } else {
        r.width = std::max(1, r.width + int(std::lround(d.x())));
        r.height = std::max(1, r.height + int(std::lround(d.y())));
    }
    emit regionEdited(m_selected, r, m_mergeKey);
    event->accept();
}

void AtlasView::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() == Qt::LeftButton && m_drag != Drag::None) {
        m_drag = Drag::None;
        event->accept();
        return;
    }
    QGraphicsView::mouseReleaseEvent(event);
}

} // namespace velvet::ui
