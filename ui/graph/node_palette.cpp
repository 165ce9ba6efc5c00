#include "ui/graph/node_palette.h"

#include "core/graph/node_catalogue.h"

#include <QGuiApplication>
#include <QKeyEvent>
#include <QLineEdit>
#include <QListWidget>
#include <QScreen>
#include <QVBoxLayout>
#include <algorithm>

namespace velvet::ui {
namespace {

QString qs(std::string_view s) {
    return QString::fromUtf8(s.data(), qsizetype(s.size()));
}

} // namespace

NodePalette::NodePalette(QWidget* parent)
    : QWidget(parent, Qt::Popup), m_filter(new QLineEdit(this)), m_list(new QListWidget(this)) {
    setObjectName(QStringLiteral("nodePalette"));
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    m_filter->setPlaceholderText(tr("Search nodes…"));
    layout->addWidget(m_filter);
    layout->addWidget(m_list);
    for (const graph::NodeType& t : graph::nodeTypes()) {
        auto* item = new QListWidgetItem(qs(t.category) + QStringLiteral(" / ") + qs(t.label));
        item->setData(Qt::UserRole, qs(t.id));
        item->setToolTip(qs(t.tooltip));
        m_list->addItem(item);
    }
    resize(260, 320);
    connect(m_filter, &QLineEdit::textChanged, this, &NodePalette::applyFilter);
    connect(m_filter, &QLineEdit::returnPressed, this, &NodePalette::choose);
    connect(m_list, &QListWidget::itemActivated, this, &NodePalette::choose);
    connect(m_list, &QListWidget::itemClicked, this, &NodePalette::choose);
    m_filter->installEventFilter(this);
}

void NodePalette::popup(QPoint at) {
    m_filter->clear();
    applyFilter(QString());
    // At the cursor, but inside the window (and its screen): near the bottom or right edge it
    // opens above or left of the cursor instead of running off the window.
    QRect bounds = parentWidget() ? parentWidget()->window()->geometry() : QRect();
    if (const QScreen* screen = QGuiApplication::screenAt(at))
        bounds = bounds.isValid() ? bounds.intersected(screen->availableGeometry())
                                  : screen->availableGeometry();
    QPoint pos = at;
    if (bounds.isValid()) {
        if (pos.y() + height() > bounds.bottom())
            pos.setY(at.y() - height());
        if (pos.x() + width() > bounds.right())
            pos.setX(at.x() - width());
        pos.setX(
            std::clamp(pos.x(), bounds.left(), std::max(bounds.left(), bounds.right() - width())));
        pos.setY(
            std::clamp(pos.y(), bounds.top(), std::max(bounds.top(), bounds.bottom() - height())));
    }
    move(pos);
    show();
    m_filter->setFocus();
}

void NodePalette::applyFilter(const QString& text) {
    const QStringList words = text.split(QLatin1Char(' '), Qt::SkipEmptyParts);
    QListWidgetItem* first = nullptr;
    for (int i = 0; i < m_list->count(); ++i) {
        QListWidgetItem* item = m_list->item(i);
        const QString hay = item->text() + QLatin1Char(' ') + item->data(Qt::UserRole).toString();
        bool match = true;
        for (const QString& w : words)
            match = match && hay.contains(w, Qt::CaseInsensitive);
        item->setHidden(!match);
        if (match && !first)
            first = item;
    }
    m_list->setCurrentItem(first);
}

void NodePalette::choose() {
    QListWidgetItem* item = m_list->currentItem();
    if (!item || item->isHidden())
        return;
    const QString id = item->data(Qt::UserRole).toString();
    hide();
    emit chosen(id);
}

bool NodePalette::eventFilter(QObject* watched, QEvent* event) {
    // Up and Down in the filter move through the visible entries.
    if (watched == m_filter && event->type() == QEvent::KeyPress) {
        const int key = static_cast<QKeyEvent*>(event)->key();
        if (key == Qt::Key_Up || key == Qt::Key_Down) {
            int row = m_list->currentRow();
            const int step = key == Qt::Key_Up ? -1 : 1;
            for (int r = row + step; r >= 0 && r < m_list->count(); r += step)
                if (!m_list->item(r)->isHidden()) {
                    m_list->setCurrentRow(r);
                    break;
                }
            return true;
        }
    }
    return QWidget::eventFilter(watched, event);
}

} // namespace velvet::ui
