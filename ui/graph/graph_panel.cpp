#include "ui/graph/graph_panel.h"

#include "ui/graph/graph_model.h"
#include "ui/graph/graph_scene.h"
#include "ui/graph/graph_view.h"

#include <QVBoxLayout>

namespace velvet::ui {

GraphPanel::GraphPanel(DocumentController* controller, QWidget* parent)
    : QWidget(parent), m_model(new GraphModel(controller, this)),
      m_scene(new GraphScene(m_model, this)), m_view(new GraphView(m_scene, this)) {
    setObjectName(QStringLiteral("graphPanel"));
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_view);
    connect(m_model, &GraphModel::editRefused, this, &GraphPanel::message);
    connect(m_scene, &QGraphicsScene::selectionChanged, this, [this] {
        const std::vector<graph::NodeId> nodes = m_scene->selectedNodes();
        emit nodeSelected(nodes.size() == 1 ? nodes.front() : graph::kInvalidNodeId);
    });
}

} // namespace velvet::ui
