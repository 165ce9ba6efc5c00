#include "ui/render_dialog.h"

#include "core/frame_pattern.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"
#include "ui/viewport_widget.h"

#include <QApplication>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QEventLoop>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPointer>
#include <QProgressDialog>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>
#include <QVBoxLayout>
#include <atomic>
#include <thread>

namespace velvet::ui {
namespace {

const char* const kLastJobKey = "render/last";

QSpinBox* sizeBox(int value, const QString& name) {
    auto* box = new QSpinBox;
    box->setRange(1, 8192);
    box->setValue(value);
    box->setSuffix(QObject::tr(" px"));
    box->setObjectName(name);
    return box;
}

} // namespace

RenderDialog::RenderDialog(QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("Render"));
    setObjectName(QStringLiteral("renderDialog"));
    m_width = sizeBox(1920, QStringLiteral("renderWidth"));
    m_height = sizeBox(1080, QStringLiteral("renderHeight"));
    m_frames = new QSpinBox;
    m_frames->setObjectName(QStringLiteral("renderFrames"));
    m_frames->setRange(1, render::kMaxTurntableFrames);
    m_frames->setToolTip(tr("1 renders a still; more renders a turntable, one full turn"));
    m_mode = new QComboBox;
    m_mode->setObjectName(QStringLiteral("renderMode"));
    m_mode->addItem(tr("Mesh turns"), int(TurntableMode::Mesh));
    m_mode->addItem(tr("HDRI and lights turn"), int(TurntableMode::Light));
    // Anti-aliasing for what leaves the editor: 2x2 by default, as a still or a turntable handed
    // to a supervisor should not show stair-stepped silhouettes (the cost, about N^2 the frame
    // time, is paid once, not per viewport frame).
    m_supersample = new QComboBox;
    m_supersample->setObjectName(QStringLiteral("renderSupersample"));
    m_supersample->addItem(tr("Off"), 1);
    for (int n = 2; n <= render::kMaxSupersample; ++n)
        m_supersample->addItem(tr("%1 × %1 samples").arg(n), n);
    m_supersample->setCurrentIndex(1);
    m_supersample->setToolTip(tr("Each frame drawn N times larger each way and averaged down: "
                                 "smooth edges, about N² the time"));
    m_output = new QLineEdit(QDir::home().filePath(QStringLiteral("render.png")));
    m_output->setObjectName(QStringLiteral("renderOutput"));
    m_output->setToolTip(tr("A .png or .exr image; for a turntable a pattern with one frame "
                            "number, e.g. turntable_%03d.png"));
    auto* browse = new QPushButton(tr("Browse…"));
    connect(browse, &QPushButton::clicked, this, &RenderDialog::browse);
    auto* outputRow = new QHBoxLayout;
    outputRow->addWidget(m_output, 1);
    outputRow->addWidget(browse);
    m_video = new QLineEdit;
    m_video->setObjectName(QStringLiteral("renderVideo"));
    m_video->setPlaceholderText(tr("optional: turntable.mp4 (needs ffmpeg)"));

    auto* form = new QFormLayout;
    auto* sizeRow = new QHBoxLayout;
    sizeRow->addWidget(m_width);
    sizeRow->addWidget(new QLabel(QStringLiteral("×")));
    sizeRow->addWidget(m_height);
    form->addRow(tr("Size"), sizeRow);
    form->addRow(tr("Anti-aliasing"), m_supersample);
    form->addRow(tr("Frames"), m_frames);
    form->addRow(tr("Turntable"), m_mode);
    form->addRow(tr("Output"), outputRow);
    form->addRow(tr("Video"), m_video);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    buttons->button(QDialogButtonBox::Ok)->setText(tr("Render"));
    buttons->button(QDialogButtonBox::Ok)->setObjectName(QStringLiteral("renderStart"));
    connect(buttons, &QDialogButtonBox::accepted, this, &RenderDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addWidget(buttons);
    connect(m_frames, &QSpinBox::valueChanged, this, &RenderDialog::framesChanged);
    framesChanged(1);
}

void RenderDialog::framesChanged(int frames) {
    const bool turntable = frames > 1;
    m_mode->setEnabled(turntable);
    m_video->setEnabled(turntable);
    // Offer a numbered name when a still's name becomes a turntable's (and back), so the field
    // is never left holding what the other kind refuses.
    const QFileInfo info(m_output->text());
    const QString text = m_output->text();
    if (turntable && !text.contains(QLatin1Char('%')))
        m_output->setText(info.dir().filePath(info.completeBaseName() + QStringLiteral("_%03d.") +
                                              info.suffix()));
    else if (!turntable && text.contains(QStringLiteral("_%03d.")))
        m_output->setText(QString(text).replace(QStringLiteral("_%03d."), QStringLiteral(".")));
}

void RenderDialog::browse() {
    const QString file =
        QFileDialog::getSaveFileName(this, tr("Render To"), m_output->text(),
                                     tr("PNG image (*.png);;OpenEXR image, scene-linear (*.exr)"),
                                     nullptr, QFileDialog::DontConfirmOverwrite);
    if (!file.isEmpty()) {
        m_output->setText(file);
        framesChanged(m_frames->value());
    }
}

render::RenderJob RenderDialog::job() const {
    render::RenderJob job;
    job.settings.width = m_width->value();
    job.settings.height = m_height->value();
    // One frame is a still (frames = 0 in RenderJob); more is a turntable.
    job.frames = m_frames->value() > 1 ? m_frames->value() : 0;
    job.mode = TurntableMode(m_mode->currentData().toInt());
    job.supersample = m_supersample->currentData().toInt();
    job.output = m_output->text().trimmed().toStdString();
    if (job.frames > 0)
        job.video = m_video->text().trimmed().toStdString();
    return job;
}

void RenderDialog::setJob(const render::RenderJob& job) {
    m_width->setValue(job.settings.width);
    m_height->setValue(job.settings.height);
    m_frames->setValue(std::max(1, job.frames));
    m_mode->setCurrentIndex(m_mode->findData(int(job.mode)));
    if (const int i = m_supersample->findData(job.supersample); i >= 0)
        m_supersample->setCurrentIndex(i);
    m_output->setText(QString::fromStdString(job.output));
    m_video->setText(QString::fromStdString(job.video));
    framesChanged(m_frames->value());
}

void RenderDialog::accept() {
    std::string why;
    if (render::checkRenderJob(job(), &why) != render::RenderJobCheck::Ok) {
        QMessageBox::warning(this, tr("Render"), QString::fromStdString(why));
        return;
    }
    QDialog::accept();
}

render::RenderJobStatus runRenderJobWithProgress(QWidget* parent, const Scene& scene,
                                                 const render::RenderJob& job, LogPanel* log,
                                                 QString* error) {
    const int total = job.frames > 0 ? job.frames : 1;
    QProgressDialog progress(QObject::tr("Rendering…"), QObject::tr("Cancel"), 0, total, parent);
    progress.setObjectName(QStringLiteral("renderProgress"));
    progress.setWindowTitle(QObject::tr("Render"));
    progress.setWindowModality(Qt::ApplicationModal);
    progress.setMinimumDuration(0);
    progress.setAutoClose(false);
    progress.setAutoReset(false);
    progress.setValue(0);
    progress.setLabelText(QObject::tr("Rendering %1 × %2, frame 1 of %3…")
                              .arg(job.settings.width)
                              .arg(job.settings.height)
                              .arg(total));

    std::atomic<bool> cancelled{false};
    QObject::connect(&progress, &QProgressDialog::canceled, [&] { cancelled = true; });
    QEventLoop loop;
    QPointer<QProgressDialog> dialog(&progress);
    render::RenderJobStatus status = render::RenderJobStatus::Failed;
    std::string message;
    Problems problems;
    // The worker makes its own headless context (runRenderJob): EGL contexts are current per
    // thread, and the viewport's stays the GUI thread's.
    std::thread worker([&] {
        status = render::runRenderJob(
            scene, job,
            [&](const render::RenderJobProgress& p) {
                const QString text =
                    p.encoding
                        ? QObject::tr("Encoding %1 with ffmpeg…")
                              .arg(QString::fromStdString(job.video))
                        : QObject::tr("Frame %1 of %2 written, %3 s elapsed, about %4 s left")
                              .arg(p.done)
                              .arg(p.total)
                              .arg(p.elapsedSeconds, 0, 'f', 1)
                              .arg(p.etaSeconds, 0, 'f', 0);
                QMetaObject::invokeMethod(
                    &loop,
                    [dialog, text, done = p.done] {
                        if (dialog) {
                            dialog->setValue(done);
                            dialog->setLabelText(text);
                        }
                    },
                    Qt::QueuedConnection);
                return !cancelled.load();
            },
            &message, &problems);
        QMetaObject::invokeMethod(&loop, &QEventLoop::quit, Qt::QueuedConnection);
    });
    loop.exec();
    worker.join();
    progress.close();
    if (log)
        for (const Problem& p : problems.items)
            log->warning(QString::fromStdString(p.toString()));
    if (error)
        *error = QString::fromStdString(message);
    return status;
}

void renderInteractively(QWidget* parent, const DocumentController& controller,
                         const ViewportWidget* viewport, LogPanel* log) {
    RenderDialog dialog(parent);
    // The last render's size, frames and names (QSettings), else the defaults.
    QSettings settings;
    if (settings.contains(QString(kLastJobKey) + "/output")) {
        render::RenderJob last;
        last.settings.width = settings.value(QString(kLastJobKey) + "/width", 1920).toInt();
        last.settings.height = settings.value(QString(kLastJobKey) + "/height", 1080).toInt();
        last.frames = settings.value(QString(kLastJobKey) + "/frames", 0).toInt();
        last.mode = TurntableMode(settings.value(QString(kLastJobKey) + "/mode", 0).toInt());
        last.supersample = settings.value(QString(kLastJobKey) + "/supersample", 2).toInt();
        last.output = settings.value(QString(kLastJobKey) + "/output").toString().toStdString();
        last.video = settings.value(QString(kLastJobKey) + "/video").toString().toStdString();
        dialog.setJob(last);
    }
    if (dialog.exec() != QDialog::Accepted)
        return;
    render::RenderJob job = dialog.job();
    settings.setValue(QString(kLastJobKey) + "/width", job.settings.width);
    settings.setValue(QString(kLastJobKey) + "/height", job.settings.height);
    settings.setValue(QString(kLastJobKey) + "/frames", job.frames);
    settings.setValue(QString(kLastJobKey) + "/mode", int(job.mode));
    settings.setValue(QString(kLastJobKey) + "/supersample", job.supersample);
    settings.setValue(QString(kLastJobKey) + "/output", QString::fromStdString(job.output));
    settings.setValue(QString(kLastJobKey) + "/video", QString::fromStdString(job.video));

    // What the viewport shows (exposure, tone mapper, view, display, time) at the dialog's size,
    // from the artist's orbit; the A/B split and the reduced resolution are viewport aids.
    const int width = job.settings.width, height = job.settings.height;
    if (viewport) {
        job.settings = viewport->frameSettings();
        job.settings.camera = viewport->viewCamera();
    }
    job.settings.width = width;
    job.settings.height = height;
    job.settings.renderScale = 1.0f;
    job.settings.splitMaterial.reset();
    job.settings.hasPreviousViewProj = false;

    QString error;
    const render::RenderJobStatus status =
        runRenderJobWithProgress(parent, controller.scene(), job, log, &error);
    const QString where = QString::fromStdString(job.video.empty() ? job.output : job.video);
    switch (status) {
    case render::RenderJobStatus::Done:
        if (log)
            log->info(QObject::tr("Rendered %1").arg(where));
        break;
    case render::RenderJobStatus::Cancelled:
        if (log)
            log->info(QObject::tr("Render cancelled; the frames written so far stay (%1)")
                          .arg(QString::fromStdString(job.output)));
        break;
    case render::RenderJobStatus::Failed:
        if (log)
            log->add(LogPanel::Severity::Error, error);
        QMessageBox::critical(parent, QObject::tr("Render"), error);
        break;
    }
}

} // namespace velvet::ui
