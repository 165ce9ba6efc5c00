#include "ui/reference/reference_panel.h"

#include "core/image_ops.h"
#include "ui/document_controller.h"
#include "ui/reference/reference_job.h"
#include "ui/viewport_widget.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QLinearGradient>
#include <QMouseEvent>
#include <QPainter>
#include <QSlider>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace velvet::ui {

namespace {

QColor toColor(glm::vec3 c) {
    const auto byte = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    return QColor(byte(c.r), byte(c.g), byte(c.b));
}

/// Height of the heat map's legend strip for @p fm.
int legendHeight(const QFontMetrics& fm) {
    return 10 + fm.height() + 6;
}

} // namespace

// ---- The split view -----------------------------------------------------------------------------

ReferenceSplitView::ReferenceSplitView(QWidget* parent) : QWidget(parent) {
    setObjectName(QStringLiteral("referenceSplitView"));
    setMinimumSize(160, 90);
    setCursor(Qt::SplitHCursor);
}

void ReferenceSplitView::setImages(const QImage& viewport, const QImage& reference) {
    m_viewport = viewport;
    m_reference = reference;
    update();
}

void ReferenceSplitView::setViewportImage(const QImage& viewport) {
    m_viewport = viewport;
    update();
}

void ReferenceSplitView::setDeltaE(const Image& deltaE, const Image& coverage) {
    m_deltaE = deltaE;
    m_coverage = coverage;
    update();
}

void ReferenceSplitView::setHeatMapShown(bool shown) {
    m_heatMap = shown;
    setCursor(shown ? Qt::ArrowCursor : Qt::SplitHCursor);
    update();
}

void ReferenceSplitView::setSplit(double split) {
    m_split = std::clamp(split, 0.0, 1.0);
    update();
}

QImage ReferenceSplitView::composed() const {
    if (m_reference.isNull())
        return {};
    if (m_heatMap) {
        QImage out(m_reference.size(), QImage::Format_RGB888);
        out.fill(Qt::black);
        if (m_deltaE.width != out.width() || m_deltaE.height != out.height() ||
            m_coverage.width != out.width() || m_coverage.height != out.height())
            return out; // no comparison for this image (yet)
        // The mesh's pixels coloured by their ΔE; around them the viewport, grey and dimmed, so
        // the map sits over what the artist sees.
        const QImage under =
            m_viewport.scaled(out.size(), Qt::IgnoreAspectRatio, Qt::SmoothTransformation)
                .convertToFormat(QImage::Format_RGB888);
        for (int y = 0; y < out.height(); ++y)
            for (int x = 0; x < out.width(); ++x) {
                if (*m_coverage.at(x, y) >= 1.0f) {
                    out.setPixelColor(x, y, toColor(heatMapColor(*m_deltaE.at(x, y), kHeatMapMax)));
                } else if (!under.isNull()) {
                    const int grey = qGray(under.pixel(x, y)) / 2;
                    out.setPixelColor(x, y, QColor(grey, grey, grey));
                }
            }
        return out;
    }
    QImage out = m_reference.convertToFormat(QImage::Format_RGB888);
    if (m_viewport.isNull())
        return out;
    const QImage left =
        m_viewport.scaled(out.size(), Qt::IgnoreAspectRatio, Qt::SmoothTransformation)
            .convertToFormat(QImage::Format_RGB888);
    const int cut = int(std::lround(m_split * out.width()));
    QPainter p(&out);
    p.drawImage(QRect(0, 0, cut, out.height()), left, QRect(0, 0, cut, out.height()));
    return out;
}

QRect ReferenceSplitView::imageRect() const {
    if (m_reference.isNull())
        return rect();
    QRect area = rect();
    if (m_heatMap)
        area.setBottom(area.bottom() - legendHeight(fontMetrics()));
    QSize size = m_reference.size();
    size.scale(area.size(), Qt::KeepAspectRatio);
    return QRect(QPoint((area.width() - size.width()) / 2, (area.height() - size.height()) / 2),
                 size);
}

void ReferenceSplitView::paintLegend(QPainter& p, const QRect& image) {
    // The ramp of heatMapColor from 0 to kHeatMapMax, under the map, with five ticks.
    const QFontMetrics fm(font());
    const int margin = fm.horizontalAdvance(QStringLiteral("ΔE00 "));
    const QRect bar(image.left() + margin, image.bottom() + 4,
                    std::max(image.width() - 2 * margin, 20), 8);
    QLinearGradient ramp(bar.topLeft(), bar.topRight());
    for (int i = 0; i <= 8; ++i)
        ramp.setColorAt(i / 8.0, toColor(heatMapColor(kHeatMapMax * i / 8.0, kHeatMapMax)));
    p.fillRect(bar, ramp);
    p.setPen(palette().windowText().color());
    p.drawText(QRect(image.left(), bar.top() - 4, margin, bar.height() + 8), Qt::AlignVCenter,
               QStringLiteral("ΔE00"));
    // Five ticks where they fit, else the ends and the middle, else the ends.
    const int widest = fm.horizontalAdvance(QStringLiteral("≥%1").arg(kHeatMapMax)) + 8;
    const int step = bar.width() >= 4 * widest ? 1 : bar.width() >= 2 * widest ? 2 : 4;
    for (int i = 0; i <= 4; i += step) {
        const int x = bar.left() + bar.width() * i / 4;
        const QString text = i == 4 ? QStringLiteral("≥%1").arg(kHeatMapMax)
                                    : QString::number(kHeatMapMax * i / 4.0);
        const int w = fm.horizontalAdvance(text);
        p.drawText(QRect(x - w / 2, bar.bottom() + 2, w + 2, fm.height()), Qt::AlignLeft, text);
    }
}

void ReferenceSplitView::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.fillRect(rect(), palette().window());
    if (m_reference.isNull()) {
        p.drawText(rect(), Qt::AlignCenter, tr("Rendering the reference…"));
        return;
    }
    const QRect r = imageRect();
    p.setRenderHint(QPainter::SmoothPixmapTransform);
    p.drawImage(r, composed());
    if (m_heatMap) {
        paintLegend(p, r);
        return;
    }
    // The divider and what each side is.
    const int x = r.left() + int(std::lround(m_split * r.width()));
    p.setPen(QPen(Qt::white, 2));
    p.drawLine(x, r.top(), x, r.bottom());
    p.setPen(Qt::white);
    const QFontMetrics fm(font());
    if (x - r.left() > fm.horizontalAdvance(tr("Viewport")) + 8)
        p.drawText(QRect(r.left() + 4, r.top() + 4, x - r.left() - 8, fm.height()), Qt::AlignLeft,
                   tr("Viewport"));
    if (r.right() - x > fm.horizontalAdvance(tr("Reference")) + 8)
        p.drawText(QRect(x + 4, r.top() + 4, r.right() - x - 8, fm.height()), Qt::AlignRight,
                   tr("Reference"));
}

void ReferenceSplitView::mousePressEvent(QMouseEvent* event) {
    mouseMoveEvent(event);
}

void ReferenceSplitView::mouseMoveEvent(QMouseEvent* event) {
    if (m_heatMap || !(event->buttons() & Qt::LeftButton))
        return;
    const QRect r = imageRect();
    setSplit(double(event->position().x() - r.left()) / std::max(r.width(), 1));
    emit splitDragged(m_split);
}

// ---- The panel ----------------------------------------------------------------------------------

ReferencePanel::ReferencePanel(DocumentController* controller, ViewportWidget* viewport,
                               QWidget* parent)
    : QWidget(parent), m_controller(controller), m_viewport(viewport),
      m_job(new ReferenceJob(this)), m_view(new ReferenceSplitView(this)),
      m_split(new QSlider(Qt::Horizontal, this)), m_heatMap(new QToolButton(this)),
      m_label(new QLabel(this)) {
    setObjectName(QStringLiteral("referencePanel"));
    m_split->setObjectName(QStringLiteral("referenceSplit"));
    m_split->setRange(0, 100);
    m_split->setValue(50);
    m_split->setToolTip(tr("Viewport left of the divider, the path-traced reference right"));
    m_heatMap->setObjectName(QStringLiteral("referenceHeatMap"));
    m_heatMap->setText(tr("ΔE heat map"));
    m_heatMap->setCheckable(true);
    m_heatMap->setToolTip(tr("Show where the viewport departs from the reference: per-pixel "
                             "CIEDE2000 after the same display transform, black 0 to red %1 and "
                             "above")
                              .arg(ReferenceSplitView::kHeatMapMax));
    m_label->setObjectName(QStringLiteral("referenceStatus"));
    m_label->setWordWrap(true);
    auto* controls = new QHBoxLayout;
    controls->addWidget(m_split, 1);
    controls->addWidget(m_heatMap);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(m_view, 1);
    layout->addLayout(controls);
    layout->addWidget(m_label);
    connect(m_split, &QSlider::valueChanged, this, [this](int v) { m_view->setSplit(v / 100.0); });
    connect(m_view, &ReferenceSplitView::splitDragged, this, [this](double s) {
        const QSignalBlocker block(m_split);
        m_split->setValue(int(std::lround(s * 100.0)));
    });
    connect(m_heatMap, &QToolButton::toggled, this, [this](bool on) {
        m_view->setHeatMapShown(on);
        m_split->setEnabled(!on); // the split has no meaning over the heat map
    });
    connect(m_job, &ReferenceJob::imageReady, this, &ReferencePanel::showFrame);
    connect(m_job, &ReferenceJob::failed, this, [this](const QString& message) {
        m_label->setText(tr("Reference failed: %1").arg(message));
        emit status(tr("Reference failed: %1").arg(message));
    });
    // Edits and orbits come in bursts: restart once the burst settles.
    m_restart.setSingleShot(true);
    m_restart.setInterval(300);
    connect(&m_restart, &QTimer::timeout, this, &ReferencePanel::restart);
    connect(m_controller, &DocumentController::sceneChanged, this,
            &ReferencePanel::scheduleRestart);
    connect(m_viewport, &ViewportWidget::viewCameraChanged, this, &ReferencePanel::scheduleRestart);
    connect(m_viewport, &ViewportWidget::settledLinearReady, this,
            &ReferencePanel::adoptSettledView);
}

ReferencePanel::~ReferencePanel() = default;

void ReferencePanel::showFrame(const ReferenceFrame& frame) {
    m_passes = frame.passes;
    m_shownVersion = frame.viewportVersion;
    m_stats = frame.stats;
    m_view->setImages(m_snapshot, frame.image);
    m_view->setDeltaE(frame.deltaE, frame.coverage);
    QString text;
    if (frame.deltaE.empty()) {
        text = tr("Reference: %1 spp (%2)")
                   .arg(frame.passes)
                   .arg(m_noComparison.isEmpty() ? tr("no viewport image to compare with")
                                                 : m_noComparison);
    } else if (frame.stats.pixels == 0) {
        text = tr("Reference: %1 spp (the mesh covers no whole pixel)").arg(frame.passes);
    } else {
        text = tr("Reference: %1 spp · ΔE2000 on the mesh: mean %2, p95 %3")
                   .arg(frame.passes)
                   .arg(frame.stats.mean, 0, 'f', 2)
                   .arg(frame.stats.p95, 0, 'f', 2);
        if (!comparesSettledView())
            text += tr(" (against the viewport's plain frame until it settles)");
    }
    m_label->setText(text + tr(" (CPU path tracer; restarts when the scene or the view changes)"));
    emit status(text);
}

void ReferencePanel::setActive(bool active) {
    if (active == m_active)
        return;
    m_active = active;
    // The viewport keeps its refinement's linear frames while the panel compares with them.
    m_viewport->setKeepsSettledLinear(active);
    if (active) {
        restart();
    } else {
        m_restart.stop();
        m_job->stop();
        emit status({});
    }
}

void ReferencePanel::scheduleRestart() {
    if (m_active)
        m_restart.start();
}

void ReferencePanel::restart() {
    if (!m_active)
        return;
    const QSize size = m_viewport->size();
    const int height = std::max(1, kWidth * std::max(size.height(), 1) / std::max(size.width(), 1));
    // The viewport as it is now, scene-linear, averaged down to the reference's size (each
    // reference pixel integrates its footprint too) and shown through the same display transform
    // as the reference: the left of the split and what the ΔE compares.
    // The view at rest where it has settled (the refinement's mean); else a frame drawn now,
    // replaced by the mean once the refinement ends (adoptSettledView).
    // A debug view's linear image holds raw values (normals, depth…), not light.
    const bool debugView = m_viewport->frameSettings().view != render::DebugView::Final;
    m_noComparison = debugView ? tr("the viewport shows a debug view: no ΔE") : QString();
    const bool settled = !debugView && !m_viewport->settledLinear().empty();
    Image grabbedLinear;
    const QImage grabbed = settled ? QImage() : m_viewport->grabFramebuffer(&grabbedLinear);
    const Image viewportDisplay =
        debugView ? Image()
                  : comparisonImage(settled ? m_viewport->settledLinear() : grabbedLinear, height);
    m_snapshot = viewportDisplay.empty() ? grabbed.scaled(kWidth, height, Qt::IgnoreAspectRatio,
                                                          Qt::SmoothTransformation)
                                         : ReferenceJob::toQImage(viewportDisplay);
    // Without the refinement the frame drawn is the view the artist sees: nothing to wait for.
    const bool atRest = settled || !m_viewport->progressiveAntialiasing();
    m_settledVersion = atRest && !viewportDisplay.empty() ? 0 : -1;
    m_viewportVersions = 0;
    const float exposure = m_viewport->frameSettings().exposureEv;
    Scene scene = m_controller->scene();
    scene.camera = m_viewport->viewCamera();
    m_passes = 0;
    m_stats = {};
    m_label->setText(tr("Rendering the reference…"));
    m_job->start(scene, kWidth, height, viewportDisplay, exposure);
}

Image ReferencePanel::comparisonImage(const Image& linear, int height) const {
    if (linear.empty())
        return {};
    std::string error;
    const Image small = velvet::resize(linear, kWidth, height, &error, ResizeFilter::Box);
    if (small.empty())
        return {};
    return ReferenceJob::displayImage(small, m_viewport->frameSettings().exposureEv);
}

void ReferencePanel::adoptSettledView() {
    // A restart still to come reads the settled mean itself; a debug view compares nothing.
    if (!m_active || m_restart.isActive() ||
        m_viewport->frameSettings().view != render::DebugView::Final || m_settledVersion >= 0)
        return;
    const Image display = comparisonImage(m_viewport->settledLinear(), m_snapshot.height());
    if (display.empty() || display.width != m_snapshot.width())
        return;
    m_snapshot = ReferenceJob::toQImage(display);
    m_view->setViewportImage(m_snapshot);
    m_job->setViewport(display);
    m_settledVersion = ++m_viewportVersions;
}

} // namespace velvet::ui
