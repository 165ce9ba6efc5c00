#pragma once
/// @file graph_panel.h
/// The "Material graph" dock's contents: the live graph model, its scene and view. Refused
/// edits come out of message() for the status bar and the Log; the selected node comes out of
/// nodeSelected() for the Properties panel.
///
/// Node thumbnails: every node that makes a texture-like value (the Texture, Noise, Math and
/// Channels categories; NodeItem::hasPreview) shows its first output as the GPU computes it. After
/// a graph change (not a move) the panel waits ~100 ms for the edits to settle, then asks its
/// preview source for one batch of every such node. The source is whoever owns a GL context (the
/// main window hands it the viewport's ViewportWidget::renderGraphPreviews); this panel makes no
/// GL call. A source that cannot draw yet (no context) returns nothing, and the batch is asked
/// again at the next previewSourceReady().

#include "core/diagnostics.h"
#include "core/graph/graph.h"
#include "core/image.h"
#include "render/graph_preview.h"

#include <QStringList>
#include <QWidget>
#include <functional>
#include <vector>

class QTimer;

namespace velvet::ui {

class DocumentController;
class GraphModel;
class GraphScene;
class GraphView;

class GraphPanel : public QWidget {
    Q_OBJECT
public:
    /// Renders thumbnails: one Image per request, or an empty vector when it cannot draw now.
    using PreviewSource = std::function<std::vector<Image>(
        const graph::Graph&, const std::vector<render::PreviewRequest>&, Problems*)>;

    explicit GraphPanel(DocumentController* controller, QWidget* parent = nullptr);

    GraphModel* model() const { return m_model; }
    GraphScene* scene() const { return m_scene; }
    GraphView* view() const { return m_view; }

    /// Sets who renders thumbnails and asks for a batch.
    void setPreviewSource(PreviewSource source);
    /// Thumbnail batches drawn since construction (tests: one per settled burst of edits).
    int previewBatchCount() const { return m_previewBatches; }
    /// The debounce between the last graph change and the batch it triggers.
    static constexpr int kPreviewDelayMs = 100;

public slots:
    /// Selects node @p id alone and centres the view on it (Properties' "driven by" links). The
    /// selection shows the node in Properties (nodeSelected). False when there is no such node.
    bool showNode(velvet::graph::NodeId id);
    /// The preview source may draw now (the viewport drew a frame): runs a batch it missed.
    void previewSourceReady();

signals:
    /// A refused edit, with the model's reason.
    void message(const QString& text);
    /// The selection became exactly node @p id, or kInvalidNodeId when it became anything else
    /// (nothing, several nodes, links only). The window shows the node in Properties.
    void nodeSelected(velvet::graph::NodeId id);
    /// A thumbnail could not be drawn (a shader or texture problem), for the Log.
    void previewProblems(const QString& text);

private:
    void schedulePreviews();
    void renderPreviews();

    GraphModel* m_model;
    GraphScene* m_scene;
    GraphView* m_view;
    PreviewSource m_previewSource;
    QTimer* m_previewTimer;
    bool m_previewMissed = false; ///< a batch found no context; run it at previewSourceReady()
    int m_previewBatches = 0;
    QStringList m_lastPreviewProblems;
};

} // namespace velvet::ui
