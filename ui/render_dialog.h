#pragma once
/// @file render_dialog.h
/// File > Render…: a still at any size up to 8192 x 8192 (not the window's), or a turntable of
/// frames with an optional video, rendered through the same code as `velvet render`
/// (render/render_job.h) on a worker thread with its own headless context, behind a progress
/// dialog that can be cancelled (docs/turntable.md).

#include "render/render_job.h"

#include <QDialog>

class QComboBox;
class QLineEdit;
class QSpinBox;

namespace velvet::ui {

class DocumentController;
class LogPanel;
class ViewportWidget;

/// The dialog: width, height, frames (1 = a still), what turns, the output file or pattern and an
/// optional video. accept() refuses (with a message box) what checkRenderJob refuses.
class RenderDialog : public QDialog {
    Q_OBJECT
public:
    explicit RenderDialog(QWidget* parent = nullptr);
    /// The job the fields describe (size, frames, mode, output, video; no scene settings).
    render::RenderJob job() const;
    /// Fills the fields from @p job (the last render's settings).
    void setJob(const render::RenderJob& job);
    void accept() override;

private:
    void framesChanged(int frames);
    void browse();

    QSpinBox* m_width;
    QSpinBox* m_height;
    QSpinBox* m_frames;
    QComboBox* m_mode;
    QComboBox* m_supersample; ///< RenderJob::supersample: samples per pixel side
    QLineEdit* m_output;
    QLineEdit* m_video;
};

/// Renders @p job of @p scene on a worker thread behind a QProgressDialog (frames done / total,
/// ETA; Cancel stops after the frame in flight, the frames written stay). Blocks with a local
/// event loop until the job ends. Problems go to @p log; a failure also to a message box.
render::RenderJobStatus runRenderJobWithProgress(QWidget* parent, const Scene& scene,
                                                 const render::RenderJob& job, LogPanel* log,
                                                 QString* error);

/// File > Render…: the dialog, then the document's scene through the viewport's camera and
/// frame settings (exposure, tone mapper, view, display) at the dialog's size.
void renderInteractively(QWidget* parent, const DocumentController& controller,
                         const ViewportWidget* viewport, LogPanel* log);

} // namespace velvet::ui
