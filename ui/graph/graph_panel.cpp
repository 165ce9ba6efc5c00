#include "ui/graph/graph_panel.h"

#include "ui/graph/graph_scene.h"
#include "ui/graph/graph_view.h"
#include "ui/graph/node_item.h"
#include "ui/models/graph_model.h"

#include <QStringList>
#include <QTimer>
#include <QVBoxLayout>

namespace velvet::ui {

GraphPanel::GraphPanel(DocumentController* controller, QWidget* parent)
    : QWidget(parent), m_model(new GraphModel(controller, this)),
      m_scene(new GraphScene(m_model, this)), m_view(new GraphView(m_scene, this)),
      m_previewTimer(new QTimer(this)) {
    setObjectName(QStringLiteral("graphPanel"));
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_view);
    connect(m_model, &GraphModel::editRefused, this, &GraphPanel::message);
    connect(m_scene, &QGraphicsScene::selectionChanged, this, [this] {
        const std::vector<graph::NodeId> nodes = m_scene->selectedNodes();
        emit nodeSelected(nodes.size() == 1 ? nodes.front() : graph::kInvalidNodeId);
    });
    // Thumbnails follow values, settings and structure; a move changes no pixel.
    m_previewTimer->setSingleShot(true);
    m_previewTimer->setInterval(kPreviewDelayMs);
    connect(m_previewTimer, &QTimer::timeout, this, &GraphPanel::renderPreviews);
    connect(m_model, &GraphModel::changed, this, [this](const graph::Change& change) {
        if (change.kind != graph::ChangeKind::Layout)
            schedulePreviews();
    });
    connect(m_model, &GraphModel::reset, this, &GraphPanel::schedulePreviews);
    // A graph from outside (a file opened, a preset picked, New): show all of it. The scene
    // rebuilt itself first (its connection is older). Edits in the panel leave the view alone.
    connect(m_model, &GraphModel::reset, m_view, &GraphView::frameAllWhenSized);
    m_view->frameAllWhenSized(); // the document's graph at start
}

bool GraphPanel::showNode(graph::NodeId id) {
    NodeItem* item = m_scene->nodeItem(id);
    if (!item)
        return false;
    m_scene->clearSelection();
    item->setSelected(true);
    m_view->centerOn(item);
    m_view->setFocus();
    return true;
}

void GraphPanel::setPreviewSource(PreviewSource source) {
    m_previewSource = std::move(source);
    schedulePreviews();
}

void GraphPanel::previewSourceReady() {
    if (m_previewMissed && !m_previewTimer->isActive())
        schedulePreviews();
}

void GraphPanel::schedulePreviews() {
    // Restarting the single-shot timer folds a burst of edits (a slider drag) into one batch.
    if (m_previewSource)
        m_previewTimer->start();
}

void GraphPanel::renderPreviews() {
    m_previewMissed = false;
    const graph::Graph& g = m_model->graph();
    std::vector<render::PreviewRequest> requests;
    std::vector<NodeItem*> items;
    for (const auto& [id, node] : g.nodes()) {
        NodeItem* item = m_scene->nodeItem(id);
        if (item && item->hasPreview()) {
            requests.push_back({id, 0});
            items.push_back(item);
        }
    }
    if (requests.empty() || !m_previewSource)
        return;
    Problems problems;
    const std::vector<Image> images = m_previewSource(g, requests, &problems);
    if (images.size() != requests.size()) {
        m_previewMissed = true; // no context yet
        return;
    }
    ++m_previewBatches;
    for (size_t i = 0; i < items.size(); ++i)
        items[i]->setPreview(images[i]);
    // Each batch redraws everything: report a problem once, not at every edit.
    QStringList lines;
    for (const Problem& p : problems.items)
        lines << QString::fromStdString(p.toString());
    for (const QString& line : lines)
        if (!m_lastPreviewProblems.contains(line))
            emit previewProblems(line);
    m_lastPreviewProblems = lines;
}

} // namespace velvet::ui
