/// @file viewport_painting.cpp
/// What ViewportWidget paints over the frame with Qt's paint engine (ui/ issues no GL itself):
/// the A/B split's divider and labels, the GPU-timings box and the error screen; and the A/B
/// split's state they show. Split from viewport_widget.cpp by job.
#include "render/renderer.h"
#include "ui/viewport_widget.h"

#include <QOpenGLContext>
#include <QOpenGLWindow>
#include <QPainter>
#include <algorithm>
#include <cmath>

namespace velvet::ui {

void ViewportWidget::setSplitMaterial(std::optional<Material> b) {
    m_splitMaterial = std::move(b);
    requestFrame();
}

void ViewportWidget::setSplitPosition(float fraction) {
    m_splitPosition = std::clamp(fraction, 0.0f, 1.0f);
    requestFrame();
}

void ViewportWidget::setSplitLabel(const QString& label) {
    m_splitLabel = label;
    postFrame(); // Qt paints the label over the frame: the refinement goes on
}

void ViewportWidget::setSplitSwapped(bool swapped) {
    m_splitSwapped = swapped;
    requestFrame();
}

int ViewportWidget::splitSeamX() const {
    // The renderer's seam is at round(position x frame width) in device pixels.
    const qreal dpr = glWindow()->devicePixelRatio();
    return int(std::lround(std::lround(m_splitPosition * frameSize().width()) / dpr));
}

bool ViewportWidget::isOnSplitB(int x) const {
    if (!m_splitMaterial)
        return false;
    return m_splitSwapped ? x < splitSeamX() : x >= splitSeamX();
}

void ViewportWidget::paintSplitDecorations(QPainter& painter, QSize size) const {
    if (!m_splitMaterial)
        return;
    // A dark line with a light core reads on bright and dark frames alike; a handle in the
    // middle says it can be dragged.
    const int seam = int(std::lround(m_splitPosition * size.width()));
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, false);
    painter.fillRect(QRect(seam - 2, 0, 4, size.height()), QColor(0, 0, 0, 160));
    painter.fillRect(QRect(seam - 1, 0, 2, size.height()), QColor(240, 240, 240));
    const QRect handle(seam - 5, size.height() / 2 - 18, 10, 36);
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setPen(QPen(QColor(0, 0, 0, 180), 1));
    painter.setBrush(QColor(240, 240, 240));
    painter.drawRoundedRect(handle, 4, 4);
    // The labels: A is the document's material, B what the toolbar says.
    QFont font = painter.font();
    font.setBold(true);
    painter.setFont(font);
    const QFontMetrics metrics(font);
    const QString a = tr("A · current material");
    const QString b = m_splitLabel.isEmpty() ? tr("B") : tr("B · %1").arg(m_splitLabel);
    const auto label = [&](const QString& text, bool leftSide) {
        const int margin = 8;
        const int room = std::max(0, (leftSide ? seam : size.width() - seam) - 2 * margin - 8);
        const QString shown = metrics.elidedText(text, Qt::ElideRight, room);
        const int w = metrics.horizontalAdvance(shown) + 12;
        const int x = leftSide ? seam - margin - w : seam + margin;
        const QRect box(x, margin, w, metrics.height() + 6);
        painter.setPen(Qt::NoPen);
        painter.setBrush(QColor(0, 0, 0, 150));
        painter.drawRoundedRect(box, 4, 4);
        painter.setPen(QColor(240, 240, 240));
        painter.drawText(box, Qt::AlignCenter, shown);
    };
    label(m_splitSwapped ? b : a, true);
    label(m_splitSwapped ? a : b, false);
    painter.restore();
}

QImage ViewportWidget::grabDecorated() {
    QImage image = grabFramebuffer(nullptr, /*settled=*/true);
    if (image.isNull() || !m_splitMaterial)
        return image;
    QPainter painter(&image);
    paintSplitDecorations(painter, image.deviceIndependentSize().toSize());
    return image;
}

void ViewportWidget::setTimingOverlayVisible(bool visible) {
    m_overlayVisible = visible;
    updateOverlay();
    postFrame(); // painted over the frame: the refinement goes on
}

bool ViewportWidget::isTimingOverlayVisible() const {
    return m_overlayVisible;
}

void ViewportWidget::updateOverlay() {
    if (!m_overlayVisible)
        return;
    if (!m_renderer) {
        m_overlayText = tr("no renderer");
        return;
    }
    // Called while painting (or with no frame yet): lastTimings reads GL queries, so only ask
    // while our context is current.
    const render::FrameTimings t = QOpenGLContext::currentContext() == glWindow()->context()
                                       ? m_renderer->lastTimings()
                                       : render::FrameTimings{};
    if (t.totalMs <= 0.0) {
        m_overlayText = tr("GPU timings unavailable");
    } else {
        m_overlayText = tr("G-buffer  %1 ms\nLighting  %2 ms\nPost      %3 ms\n"
                           "Total     %4 ms")
                            .arg(t.gbufferMs, 6, 'f', 2)
                            .arg(t.lightingMs, 6, 'f', 2)
                            .arg(t.postMs, 6, 'f', 2)
                            .arg(t.totalMs, 6, 'f', 2);
    }
}

void ViewportWidget::paintOverlay() {
    // Child widgets cannot sit over a native GL window, so Qt's paint engine draws the box (the
    // look of the former QLabel overlay) and the A/B divider; ui/ issues no GL itself.
    const bool timings = m_overlayVisible && !m_overlayText.isEmpty();
    if (!timings && !m_splitMaterial)
        return;
    QPainter painter(glWindow());
    paintSplitDecorations(painter, glWindow()->size());
    if (!timings)
        return;
    QFont font(QStringLiteral("monospace"));
    font.setStyleHint(QFont::Monospace);
    painter.setFont(font);
    const QRect text = painter.fontMetrics()
                           .boundingRect(QRect(0, 0, 1000, 1000), Qt::AlignLeft, m_overlayText)
                           .translated(12, 12);
    painter.fillRect(text.adjusted(-4, -4, 4, 4), QColor(0, 0, 0, 150));
    painter.setPen(QColor(0xe0, 0xe0, 0xe0));
    painter.drawText(text, Qt::AlignLeft, m_overlayText);
}

void ViewportWidget::paintError() {
    // QPainter on the QOpenGLWindow: Qt's paint engine draws the message, ui/ issues no GL itself.
    QPainter painter(glWindow());
    const QRect rect(QPoint(0, 0), glWindow()->size());
    painter.fillRect(rect, QColor(40, 40, 40));
    painter.setPen(QColor(230, 120, 120));
    painter.drawText(rect.adjusted(16, 16, -16, -16), Qt::AlignCenter | Qt::TextWordWrap,
                     m_error.isEmpty() ? tr("No renderer") : m_error);
}

} // namespace velvet::ui
