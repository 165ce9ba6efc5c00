#pragma once
/// @file reference_panel.h
/// The Reference view (issue 15): the offline path tracer's image of what the viewport shows,
/// rendered progressively in the background (ReferenceJob) and shown against a snapshot of the
/// viewport, either with a split the artist drags (viewport left of the divider, reference
/// right) or as the per-pixel CIEDE2000 heat map (the Heat map toggle). Both images go through
/// the same display transform (ReferenceJob::displayImage); the mean and 95th-percentile ΔE
/// go to the status bar as the reference converges. It restarts when the scene or the view
/// changes, and stops while the dock is hidden. View > Reference (Ctrl+Shift+R) shows it.

#include "core/image.h"
#include "core/image_compare.h"

#include <QImage>
#include <QTimer>
#include <QWidget>

class QLabel;
class QSlider;
class QToolButton;

namespace velvet::ui {

class DocumentController;
class ReferenceJob;
struct ReferenceFrame;
class ViewportWidget;

/// Paints the viewport snapshot and the reference side by side across a movable divider, or the
/// ΔE heat map of the two with its legend.
class ReferenceSplitView : public QWidget {
    Q_OBJECT
public:
    explicit ReferenceSplitView(QWidget* parent = nullptr);
    void setImages(const QImage& viewport, const QImage& reference);
    /// The viewport's side alone (the reference's stays).
    void setViewportImage(const QImage& viewport);
    /// The per-pixel ΔE the heat map shows and the reference's coverage of each pixel by the
    /// mesh (both one channel, the images' size; empty: none yet).
    void setDeltaE(const Image& deltaE, const Image& coverage);
    const Image& coverage() const { return m_coverage; }
    /// Shows the heat map (true) or the split (false).
    void setHeatMapShown(bool shown);
    bool heatMapShown() const { return m_heatMap; }
    /// Divider position in [0, 1] of the width (0: all reference, 1: all viewport).
    void setSplit(double split);
    double split() const { return m_split; }
    /// What is drawn, at the images' own size (tests compare it pixel by pixel): the split, or
    /// in heat-map mode heatMapColor(ΔE, kHeatMapMax) on each pixel the mesh covers and the
    /// viewport's luminance at half strength (grey) elsewhere (without the legend).
    QImage composed() const;
    /// Where the images are drawn in the widget (aspect kept, centred, the legend's strip below
    /// in heat-map mode).
    QRect imageRect() const;
    /// ΔE at the top of the heat map's scale (`velvet compare`'s default).
    static constexpr double kHeatMapMax = 10.0;

signals:
    void splitDragged(double split);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;

private:
    void paintLegend(QPainter& p, const QRect& image);

    QImage m_viewport, m_reference;
    Image m_deltaE, m_coverage;
    double m_split = 0.5;
    bool m_heatMap = false;
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
    /// The ΔE of the image shown against the viewport's snapshot over the pixels the mesh
    /// covers (pixels 0: none yet).
    const DeltaEStats& deltaEStats() const { return m_stats; }
    /// Whether the image shown is compared with the viewport at rest: the mean of its
    /// refinement's frames (ViewportWidget::settledLinear), which on a mesh that traces its own
    /// light holds every bounce the settled view shows. Until the view settles the comparison
    /// is with one frame drawn when the reference started.
    bool comparesSettledView() const { return m_passes > 0 && m_shownVersion == m_settledVersion; }
    ReferenceSplitView* view() const { return m_view; }
    /// Width in pixels the reference renders at (its height follows the viewport's aspect).
    static constexpr int kWidth = 160;

public slots:
    /// The viewport's frame settings changed (exposure, debug view): restarts like an edit.
    void viewStateChanged() { scheduleRestart(); }

signals:
    /// One line for the status bar ("Reference: 16 spp · ΔE2000 mean 1.84, p95 4.10").
    void status(const QString& text);

private:
    void restart();
    void scheduleRestart();
    void showFrame(const ReferenceFrame& frame);
    /// The viewport settled: its refinement's mean becomes the comparison.
    void adoptSettledView();
    /// The viewport's scene-linear @p linear averaged down to @p height rows of kWidth and
    /// through the reference's display transform (empty when it cannot be made).
    Image comparisonImage(const Image& linear, int height) const;

    DocumentController* m_controller;
    ViewportWidget* m_viewport;
    ReferenceJob* m_job;
    ReferenceSplitView* m_view;
    QSlider* m_split;
    QToolButton* m_heatMap;
    QLabel* m_label;
    QTimer m_restart;
    QImage m_snapshot;
    QString m_noComparison; ///< why the viewport's image is not compared (a debug view), or empty
    DeltaEStats m_stats;
    bool m_active = false;
    int m_passes = 0;
    int m_shownVersion = 0;     ///< ReferenceFrame::viewportVersion of the image shown
    int m_settledVersion = -1;  ///< the job's viewport version that is the settled view, or -1
    int m_viewportVersions = 0; ///< setViewport calls since the job started
};

} // namespace velvet::ui
