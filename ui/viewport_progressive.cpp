/// @file viewport_progressive.cpp
/// The viewport's progressive anti-aliasing at rest (ViewportWidget's "Progressive
/// anti-aliasing" group; render/progressive_accumulation.h): when to draw the next jittered
/// frame, and when to stop. Split from viewport_widget.cpp by job.
#include "ui/viewport_widget.h"

#include <QTimer>

namespace velvet::ui {

void ViewportWidget::setProgressiveAntialiasing(bool enabled) {
    if (enabled == m_progressiveEnabled)
        return;
    m_progressiveEnabled = enabled;
    requestFrame(); // off: the plain frame again; on: the refinement after the pause
}

void ViewportWidget::restartProgressive() {
    m_progressiveIndex = -1;
    m_progressiveShown = 0; // the mean on screen is the last view's, gone at the next frame
    m_progressiveTimer->stop();
    m_linearMean.clear();
    m_settledLinear = Image();
}

void ViewportWidget::setKeepsSettledLinear(bool keep) {
    if (keep == m_keepSettledLinear)
        return;
    m_keepSettledLinear = keep;
    m_linearMean.clear();
    m_settledLinear = Image();
    // A refinement under way or ended drew its frames without their linear images: draw it
    // again (the plain frame first, as after a change), this time keeping them.
    if (keep && m_progressiveIndex >= 0) {
        restartProgressive();
        postFrame();
    }
}

void ViewportWidget::keepLinearFrame(const render::FrameSettings& settings) {
    if (!m_keepSettledLinear || settings.accumulation < 0)
        return;
    const Image frame = m_renderer->readLinear();
    if (frame.empty())
        return;
    // The renderer's mean restarts at its frame 0 (and when the size changed, which ImageMean
    // notices itself): so does ours.
    if (m_renderer->accumulatedSamples() == 1)
        m_linearMean.clear();
    m_linearMean.add(frame);
    if (m_linearMean.count() < kProgressiveSamples ||
        m_renderer->accumulatedSamples() != m_linearMean.count())
        return;
    m_settledLinear = m_linearMean.takeMean();
    emit settledLinearReady();
}

void ViewportWidget::progressiveFrameDrawn(const render::FrameSettings& settings) {
    if (settings.accumulation >= 0) {
        // The renderer's count, not ours: a mean it restarted (the size changed) goes on from
        // its own first frame.
        m_progressiveShown = m_renderer->accumulatedSamples();
        m_progressiveIndex = m_progressiveShown;
        m_progressiveSize = QSize(settings.width, settings.height);
    } else {
        m_progressiveShown = 0;
    }
    // Still: nothing the next frames would differ by but the jitter. A drag, reduced frames,
    // an animation, textures loading, a mesh baking or a graph or a specialised lighting
    // program compiling each bring frames of their own, and refining between them would only
    // delay those.
    const bool still = m_progressiveEnabled && settings.renderScale == 1.0f && !m_interacting &&
                       m_drag == Drag::None && !m_flyTimer->isActive() && !isAnimating() &&
                       !m_renderer->graphPending() && !m_renderer->meshBakePending() &&
                       !m_renderer->specialisationPending() &&
                       m_renderer->textureProgress().loading == 0;
    if (!still) {
        m_progressiveTimer->stop();
        return;
    }
    if (m_progressiveIndex < 0) // a plain frame: refine once the changes pause
        m_progressiveTimer->start(kProgressiveDelayMs);
    else if (m_progressiveIndex < kProgressiveSamples) // the next one at the next turn
        m_progressiveTimer->start(0);
    else
        m_progressiveTimer->stop(); // converged: nothing more to draw
}

void ViewportWidget::progressiveStep() {
    if (!m_progressiveEnabled || !m_renderer)
        return;
    if (m_progressiveIndex < 0)
        m_progressiveIndex = 0;
    postFrame();
}

} // namespace velvet::ui
