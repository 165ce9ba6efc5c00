#pragma once
/// @file node_palette.h
/// The searchable node menu (Tab or right click in the graph view): a filter line over the
/// catalogue's node types (label, category and id match), Enter or a click adds the chosen one.

#include <QWidget>

class QLineEdit;
class QListWidget;

namespace velvet::ui {

class NodePalette : public QWidget {
    Q_OBJECT
public:
    explicit NodePalette(QWidget* parent = nullptr);
    /// Shows the palette at global position @p at with an empty filter and focus in it.
    void popup(QPoint at);
    QLineEdit* filter() const { return m_filter; }
    QListWidget* list() const { return m_list; }

signals:
    /// A node type was chosen (its catalogue id).
    void chosen(const QString& typeId);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void applyFilter(const QString& text);
    void choose();

    QLineEdit* m_filter;
    QListWidget* m_list;
};

} // namespace velvet::ui
