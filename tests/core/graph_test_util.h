#pragma once
// Shared helpers of the material-graph tests (tests/core and tests/render): graphs built in code
// by type id and port name, stopping the test binary with a message when a name is wrong (a typo
// in a test, not a case under test).

#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"

#include <QtGlobal>
#include <string>
#include <string_view>

namespace velvet::test {

/// The index of input @p name of node @p id.
inline graph::PortIndex inputPort(const graph::Graph& g, graph::NodeId id, std::string_view name) {
    const int i = g.node(id)->type->inputIndex(name);
    if (i < 0)
        qFatal("no input %s", std::string(name).c_str());
    return graph::PortIndex(i);
}

/// The index of output @p name of node @p id.
inline graph::PortIndex outputPort(const graph::Graph& g, graph::NodeId id, std::string_view name) {
    const int i = g.node(id)->type->outputIndex(name);
    if (i < 0)
        qFatal("no output %s", std::string(name).c_str());
    return graph::PortIndex(i);
}

/// The connection from output @p output of @p from to input @p input of @p to (not made).
inline graph::Connection link(const graph::Graph& g, graph::NodeId from, std::string_view output,
                              graph::NodeId to, std::string_view input) {
    return {from, outputPort(g, from, output), to, inputPort(g, to, input)};
}

/// Adds a node of type @p type and returns its id.
inline graph::NodeId add(graph::Graph& g, std::string_view type) {
    const graph::EditResult r = g.addNode(type);
    if (!r)
        qFatal("addNode %s: %s", std::string(type).c_str(), r.message.c_str());
    return r.node;
}

/// Makes connection @p c, which the test expects the model to accept.
inline void mustConnect(graph::Graph& g, const graph::Connection& c) {
    const graph::EditResult r = g.connect(c);
    if (!r)
        qFatal("connect: %s", r.message.c_str());
}

} // namespace velvet::test
