#pragma once
/// @file reference_panel.h
/// The Reference view (issue 15): the offline path tracer's image of what the viewport shows,
/// rendered progressively in the background (ReferenceJob) and shown against a snapshot of the
/// viewport with a split the artist drags: viewport left of the divider, reference right. It
/// restarts when the scene or the view changes, and stops while the dock is hidden.
/// View > Reference (Ctrl+Shift+R) shows it.

#include <QImage>
#include <QTimer>
#include <QWidget>

class QLabel;
class QSlider;

namespace velvet::ui {

class DocumentController;
class ReferenceJob;
class ViewportWidget;

/// Paints the viewport snapshot and the reference side by side across a movable divider.
class ReferenceSplitView : public QWidget {
    Q_OBJECT
public:
    explicit ReferenceSplitView(QWidget* parent = nullptr);
    void setImages(const QImage& viewport, const QImage& reference);
    /// Divider position in [0, 1] of the width (0: all reference, 1: all viewport).
    void setSplit(double split);
    double split() const { return m_split; }
    /// What is drawn, at the images' own size (tests compare it pixel by pixel).
    QImage composed() const;
    /// Where the images are drawn in the widget (aspect kept, centred).
    QRect imageRect() const;

signals:
    void splitDragged(double split);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;

private:
    QImage m_viewport, m_reference;
    double m_split = 0.5;
};

class ReferencePanel : public QWidget {
    Q_OBJECT
public:
    ReferencePanel(DocumentController* controller, ViewportWidget* viewport,
                   QWidget* parent = nullptr);
    ~ReferencePanel() override;

    /// Starts (true) or stops (false) rendering; the dock calls it as it is shown and hidden.
    void setActive(bool active);
    bool active() const { return m_active; }
    /// Samples per pixel of the image shown (0: none yet).
    int passes() const { return m_passes; }
    ReferenceSplitView* view() const { return m_view; }
    /// Width in pixels the reference renders at (its height follows the viewport's aspect).
    static constexpr int kWidth = 160;

signals:
    /// One line for the status bar ("Reference: 16 samples per pixel").
    void status(const QString& text);

private:
    void restart();
    void scheduleRestart();

    DocumentController* m_controller;
    ViewportWidget* m_viewport;
    ReferenceJob* m_job;
    ReferenceSplitView* m_view;
    QSlider* m_split;
    QLabel* m_label;
    QTimer m_restart;
    QImage m_snapshot;
    bool m_active = false;
    int m_passes = 0;
};

} // namespace velvet::ui
