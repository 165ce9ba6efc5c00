#include "ui/reference/reference_panel.h"

#include "ui/document_controller.h"
#include "ui/reference/reference_job.h"
#include "ui/viewport_widget.h"

#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QSlider>
#include <QVBoxLayout>
#include <algorithm>

namespace velvet::ui {

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

void ReferenceSplitView::setSplit(double split) {
    m_split = std::clamp(split, 0.0, 1.0);
    update();
}

QImage ReferenceSplitView::composed() const {
    if (m_reference.isNull())
        return {};
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
    QSize size = m_reference.size();
    size.scale(this->size(), Qt::KeepAspectRatio);
    return QRect(QPoint((width() - size.width()) / 2, (height() - size.height()) / 2), size);
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
    if (!(event->buttons() & Qt::LeftButton))
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
      m_split(new QSlider(Qt::Horizontal, this)), m_label(new QLabel(this)) {
    setObjectName(QStringLiteral("referencePanel"));
    m_split->setObjectName(QStringLiteral("referenceSplit"));
    m_split->setRange(0, 100);
    m_split->setValue(50);
    m_split->setToolTip(tr("Viewport left of the divider, the path-traced reference right"));
    m_label->setObjectName(QStringLiteral("referenceStatus"));
    m_label->setWordWrap(true);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(m_view, 1);
    layout->addWidget(m_split);
    layout->addWidget(m_label);
    connect(m_split, &QSlider::valueChanged, this, [this](int v) { m_view->setSplit(v / 100.0); });
    connect(m_view, &ReferenceSplitView::splitDragged, this, [this](double s) {
        const QSignalBlocker block(m_split);
        m_split->setValue(int(std::lround(s * 100.0)));
    });
    connect(m_job, &ReferenceJob::imageReady, this, [this](const QImage& image, int passes) {
        m_passes = passes;
        m_view->setImages(m_snapshot, image);
        const QString text = tr("Reference: %1 samples per pixel (CPU path tracer; restarts when "
                                "the scene or the view changes)")
                                 .arg(passes);
        m_label->setText(text);
        emit status(tr("Reference: %1 samples per pixel").arg(passes));
    });
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
}

ReferencePanel::~ReferencePanel() = default;

void ReferencePanel::setActive(bool active) {
    if (active == m_active)
        return;
    m_active = active;
    if (active) {
        restart();
    } else {
        m_restart.stop();
        m_job->stop();
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
    // The viewport as it is now, at the reference's size: the left of the split.
    m_snapshot = m_viewport->grabFramebuffer().scaled(kWidth, height, Qt::IgnoreAspectRatio,
                                                      Qt::SmoothTransformation);
    Scene scene = m_controller->scene();
    scene.camera = m_viewport->viewCamera();
    m_passes = 0;
    m_label->setText(tr("Rendering the reference…"));
    m_job->start(scene, kWidth, height);
}

} // namespace velvet::ui
