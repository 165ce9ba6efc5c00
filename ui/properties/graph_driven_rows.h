#pragma once
/// @file graph_driven_rows.h
/// Properties' material page, for parameters a material graph drives (issue 17 item 5): under
/// each such parameter a link "Driven by Weave (node 3) in the graph" that jumps to that node;
/// the parameter's own editor is disabled (the viewport draws the graph's value per pixel, so
/// its own value would change nothing).

#include "core/graph/graph_types.h"
#include "core/material.h"

#include <QObject>
#include <vector>

class QFormLayout;
class QToolButton;
class QWidget;

namespace velvet::ui {

class GraphDrivenRows : public QObject {
    Q_OBJECT
public:
    explicit GraphDrivenRows(QObject* parent = nullptr);

    /// Adds the (hidden) link row for @p id under @p editor, in @p form.
    void add(ParamId id, QFormLayout* form, QWidget* editor);
    /// Shows the links of the parameters @p material's graph drives, hides the others.
    void refresh(const Material& material);
    /// The node driving @p id, or kInvalidNodeId.
    graph::NodeId driver(ParamId id) const;
    /// The link of @p id (named "drivenBy:<param id>"), or null.
    QToolButton* link(ParamId id) const;

signals:
    /// The artist clicked the link of a parameter driven by node @p id.
    void nodeRequested(velvet::graph::NodeId id);

private:
    struct Row {
        ParamId id{};
        QFormLayout* form = nullptr;
        QWidget* editor = nullptr;
        QToolButton* link = nullptr;
        graph::NodeId driver = graph::kInvalidNodeId;
    };
    std::vector<Row> m_rows;
};

} // namespace velvet::ui
