#include "ui/properties/graph_driven_rows.h"

#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"
#include "render/renderer.h"

#include <QFormLayout>
#include <QToolButton>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), qsizetype(s.size()));
}

} // namespace

GraphDrivenRows::GraphDrivenRows(QObject* parent) : QObject(parent) {}

void GraphDrivenRows::add(ParamId id, QFormLayout* form, QWidget* editor) {
    auto* link = new QToolButton(editor->parentWidget());
    link->setObjectName(QStringLiteral("drivenBy:") + fromView(paramMeta(id).id));
    link->setAutoRaise(true);
    link->setToolButtonStyle(Qt::ToolButtonTextOnly);
    link->setCursor(Qt::PointingHandCursor);
    link->setStyleSheet(QStringLiteral("QToolButton { color: palette(link); text-align: left; }"));
    form->addRow(QString(), link);
    form->setRowVisible(link, false);
    const size_t index = m_rows.size();
    m_rows.push_back({id, form, editor, link, graph::kInvalidNodeId});
    connect(link, &QToolButton::clicked, this, [this, index] {
        if (m_rows[index].driver != graph::kInvalidNodeId)
            emit nodeRequested(m_rows[index].driver);
    });
}

void GraphDrivenRows::refresh(const Material& material) {
    const graph::Graph* g = material.graph.get();
    const graph::NodeId out = g ? g->outputNode() : graph::kInvalidNodeId;
    for (Row& row : m_rows) {
        const int port = graph::outputInputForParam(row.id);
        const graph::Connection* link = out != graph::kInvalidNodeId && port >= 0
                                            ? g->connectionTo(out, graph::PortIndex(port))
                                            : nullptr;
        const graph::Node* from = link ? g->node(link->outNode) : nullptr;
        row.driver = from ? from->id : graph::kInvalidNodeId;
        if (!from) {
            row.form->setRowVisible(row.link, false);
            row.editor->setEnabled(true);
            continue;
        }
        const graph::NodeType& outType = *g->node(out)->type;
        const bool perPixel = render::graphOutputIsPerPixel(outType.inputs[size_t(port)].name);
        const QString node = tr("%1 (node %2)").arg(fromView(from->type->label)).arg(from->id);
        row.link->setText(
            perPixel ? tr("Driven by %1 in the graph — show").arg(node)
                     : tr("Graph: %1 (exports); the viewport uses this value — show").arg(node));
        row.link->setToolTip(
            perPixel ? tr("The material graph's %1 feeds this parameter, so its own value is not "
                          "used; click to select the node")
                           .arg(node)
                     : tr("The material graph's %1 feeds this parameter in exports; the viewport "
                          "cannot draw it per pixel and uses the value here; click to select "
                          "the node")
                           .arg(node));
        row.form->setRowVisible(row.link, true);
        row.editor->setEnabled(!perPixel);
    }
}

graph::NodeId GraphDrivenRows::driver(ParamId id) const {
    for (const Row& row : m_rows)
        if (row.id == id)
            return row.driver;
    return graph::kInvalidNodeId;
}

QToolButton* GraphDrivenRows::link(ParamId id) const {
    for (const Row& row : m_rows)
        if (row.id == id)
            return row.link;
    return nullptr;
}

} // namespace velvet::ui
