#include "ui/properties/graph_driven_rows.h"

#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"

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
        // The viewport draws every graph output per pixel (render/lobe_channels.h): the
        // parameter's own value changes nothing while a node drives it.
        const QString node = tr("%1 (node %2)").arg(fromView(from->type->label)).arg(from->id);
        row.link->setText(tr("Driven by %1 in the graph — show").arg(node));
        row.link->setToolTip(tr("The material graph's %1 feeds this parameter, so its own value "
                                "is not used; click to select the node")
                                 .arg(node));
        row.form->setRowVisible(row.link, true);
        row.editor->setEnabled(false);
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
