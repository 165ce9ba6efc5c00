#include "ui/post_chain/post_chain_panel.h"

#include "core/post_chain_io.h"
#include "core/post_effects.h"
#include "core/resources.h"
#include "ui/commands/post_chain_commands.h"
#include "ui/document_controller.h"
#include "ui/models/post_chain_model.h"

#include <QDragEnterEvent>
#include <QDragMoveEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

QToolButton* makeButton(QWidget* parent, const char* name, const QString& text,
                        const QString& tip) {
    auto* button = new QToolButton(parent);
    button->setObjectName(QLatin1String(name));
    button->setText(text);
    button->setToolTip(tip);
    button->setAutoRaise(true);
    return button;
}

/// Where an effect of @p stage goes in @p chain: after every constrained effect of the same or an
/// earlier stage, before the first of a later stage.
size_t stageInsertPosition(const PostChain& chain, PostStage stage) {
    size_t at = chain.effects.size();
    for (size_t i = 0; i < chain.effects.size(); ++i) {
        const EffectMeta* meta = findPostEffect(chain.effects[i].type);
        if (meta && meta->stage != PostStage::Any && meta->stage > stage) {
            at = i;
            break;
        }
    }
    return at;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// PostChainListView

PostChainListView::PostChainListView(QWidget* parent) : QListView(parent) {
    setObjectName(QStringLiteral("postChainList"));
    setSelectionMode(QAbstractItemView::SingleSelection);
    setDragEnabled(true);
    setAcceptDrops(true);
    setDropIndicatorShown(true);
    setDragDropMode(QAbstractItemView::InternalMove);
    setDefaultDropAction(Qt::MoveAction);
    setMovement(QListView::Snap);
    setUniformItemSizes(true);
}

int PostChainListView::insertPositionAt(const QPoint& pos) const {
    const int rows = model() ? model()->rowCount() : 0;
    const QModelIndex index = indexAt(pos);
    if (!index.isValid())
        return pos.y() < 0 ? 0 : rows;
    const QRect rect = visualRect(index);
    return pos.y() < rect.center().y() ? index.row() : index.row() + 1;
}

void PostChainListView::dragEnterEvent(QDragEnterEvent* event) {
    if (event->mimeData()->hasFormat(QString::fromLatin1(PostChainModel::kMimeType))) {
        QListView::dragEnterEvent(event); // drop indicator, auto scroll
        event->setDropAction(Qt::MoveAction);
        event->accept();
        return;
    }
    event->ignore();
}

void PostChainListView::dragMoveEvent(QDragMoveEvent* event) {
    if (event->mimeData()->hasFormat(QString::fromLatin1(PostChainModel::kMimeType))) {
        QListView::dragMoveEvent(event);
        event->setDropAction(Qt::MoveAction);
        event->accept();
        return;
    }
    event->ignore();
}

void PostChainListView::dropEvent(QDropEvent* event) {
    const QString format = QString::fromLatin1(PostChainModel::kMimeType);
    auto* chainModel = qobject_cast<PostChainModel*>(model());
    if (!chainModel || !event->mimeData()->hasFormat(format)) {
        event->ignore();
        return;
    }
    bool ok = false;
    const int from = event->mimeData()->data(format).toInt(&ok);
    const int insertBefore = insertPositionAt(event->position().toPoint());
    stopAutoScroll();
    setState(QAbstractItemView::NoState);
    viewport()->update();
    if (!ok) {
        event->ignore();
        return;
    }
    if (chainModel->moveToInsertPosition(from, insertBefore)) {
        const int to = insertBefore > from ? insertBefore - 1 : insertBefore;
        setCurrentIndex(chainModel->index(to));
    }
    // The move is done: the drag's source must not remove anything (the model has no removeRows,
    // and CopyAction tells QAbstractItemView::startDrag so).
    event->setDropAction(Qt::CopyAction);
    event->accept();
}

void PostChainListView::keyPressEvent(QKeyEvent* event) {
    if (event->modifiers() & Qt::ControlModifier) {
        if (event->key() == Qt::Key_Up) {
            emit moveRequested(-1);
            return;
        }
        if (event->key() == Qt::Key_Down) {
            emit moveRequested(+1);
            return;
        }
        if (event->key() == Qt::Key_D) {
            emit duplicateRequested();
            return;
        }
    }
    if (event->key() == Qt::Key_Delete && event->modifiers() == Qt::NoModifier) {
        emit removeRequested();
        return;
    }
    QListView::keyPressEvent(event);
}

// ---------------------------------------------------------------------------------------------
// PostChainPanel

PostChainPanel::PostChainPanel(DocumentController* controller, QWidget* parent)
    : QWidget(parent), m_controller(controller), m_model(new PostChainModel(controller, this)),
      m_list(new PostChainListView(this)) {
    setObjectName(QStringLiteral("postChainPanel"));
    m_list->setModel(m_model);

    m_addButton = makeButton(this, "postChainAdd", tr("Add"), tr("Add an effect"));
    m_addButton->setPopupMode(QToolButton::InstantPopup);
    m_addMenu = new QMenu(m_addButton);
    m_addMenu->setObjectName(QStringLiteral("postChainAddMenu"));
    m_addButton->setMenu(m_addMenu);
    buildAddMenu();
    m_removeButton = makeButton(this, "postChainRemove", tr("Remove"),
                                tr("Remove the selected effect (Delete)"));
    m_duplicateButton = makeButton(this, "postChainDuplicate", tr("Duplicate"),
                                   tr("Duplicate the selected effect (Ctrl+D)"));
    m_upButton = makeButton(this, "postChainUp", QStringLiteral("\u2191"),
                            tr("Move the selected effect up (Ctrl+Up, or drag it)"));
    m_downButton = makeButton(this, "postChainDown", QStringLiteral("\u2193"),
                              tr("Move the selected effect down (Ctrl+Down, or drag it)"));
    auto* load = makeButton(this, "postChainLoad", tr("Load…"), tr("Load a chain preset"));
    auto* save = makeButton(this, "postChainSave", tr("Save…"), tr("Save the chain as a preset"));

    auto* buttons = new QHBoxLayout;
    buttons->setContentsMargins(0, 0, 0, 0);
    for (QToolButton* b :
         {m_addButton, m_removeButton, m_duplicateButton, m_upButton, m_downButton})
        buttons->addWidget(b);
    buttons->addStretch(1);
    // Load and Save under the list: one row of seven buttons made the panel (and the Log it is
    // tabbed with) 400 px wide at least, leaving the graph beside them no room (issue 17 item 2).
    auto* files = new QHBoxLayout;
    files->setContentsMargins(0, 0, 0, 0);
    files->addStretch(1);
    files->addWidget(load);
    files->addWidget(save);

    m_issueLabel = new QLabel(this);
    m_issueLabel->setObjectName(QStringLiteral("postChainIssues"));
    m_issueLabel->setWordWrap(true);
    m_issueLabel->setTextFormat(Qt::PlainText);
    m_issueLabel->hide();

    auto* layout = new QVBoxLayout(this);
    layout->addLayout(buttons);
    layout->addWidget(m_list, 1);
    layout->addWidget(m_issueLabel);
    layout->addLayout(files);

    connect(m_removeButton, &QToolButton::clicked, this, &PostChainPanel::removeCurrent);
    connect(m_duplicateButton, &QToolButton::clicked, this, &PostChainPanel::duplicateCurrent);
    connect(m_upButton, &QToolButton::clicked, this, [this] { moveCurrent(-1); });
    connect(m_downButton, &QToolButton::clicked, this, [this] { moveCurrent(+1); });
    connect(load, &QToolButton::clicked, this, &PostChainPanel::loadPresetDialog);
    connect(save, &QToolButton::clicked, this, &PostChainPanel::savePresetDialog);
    connect(m_list, &PostChainListView::moveRequested, this, &PostChainPanel::moveCurrent);
    connect(m_list, &PostChainListView::removeRequested, this, &PostChainPanel::removeCurrent);
    connect(m_list, &PostChainListView::duplicateRequested, this,
            &PostChainPanel::duplicateCurrent);
    connect(m_list->selectionModel(), &QItemSelectionModel::currentChanged, this, [this] {
        updateActions();
        emit effectSelected(effectAt(currentRow()));
    });
    // A click on the row already current shows its parameters again (after a graph node was
    // shown in Properties, say).
    connect(m_list, &QAbstractItemView::clicked, this,
            [this](const QModelIndex& index) { emit effectSelected(effectAt(index.row())); });
    connect(m_model, &QAbstractItemModel::modelReset, this, [this] {
        updateActions();
        emit effectSelected(effectAt(currentRow()));
    });
    connect(m_controller, &DocumentController::postChainChanged, this, [this] {
        updateIssues();
        updateActions();
    });
    updateIssues();
    updateActions();
}

PostChainPanel::~PostChainPanel() = default;

void PostChainPanel::buildAddMenu() {
    for (int s = 0; s <= static_cast<int>(PostStage::Any); ++s) {
        const auto stage = static_cast<PostStage>(s);
        bool first = true;
        for (const EffectMeta& meta : postEffectCatalogue()) {
            if (meta.stage != stage)
                continue;
            if (first) {
                m_addMenu->addSection(tr("%1 stage").arg(fromView(postStageName(stage))));
                first = false;
            }
            QAction* act = m_addMenu->addAction(fromView(meta.label));
            act->setObjectName(QStringLiteral("addEffect:") + fromView(meta.type));
            act->setData(fromView(meta.type));
            act->setToolTip(fromView(meta.description));
            const QString type = fromView(meta.type);
            connect(act, &QAction::triggered, this, [this, type] { addEffect(type); });
        }
    }
    m_addMenu->setToolTipsVisible(true);
}

EffectId PostChainPanel::effectAt(int row) const {
    const auto& effects = m_controller->scene().post.effects;
    return row >= 0 && row < int(effects.size()) ? effects[size_t(row)].id : 0;
}

int PostChainPanel::currentRow() const {
    const QModelIndex index = m_list->currentIndex();
    return index.isValid() ? index.row() : -1;
}

void PostChainPanel::setCurrentRow(int row) {
    if (row >= 0 && row < m_model->rowCount())
        m_list->setCurrentIndex(m_model->index(row));
    else
        m_list->setCurrentIndex({});
}

bool PostChainPanel::addEffect(const QString& type) {
    const EffectMeta* meta = findPostEffect(type.toStdString());
    if (!meta)
        return false;
    const PostChain& chain = m_controller->scene().post;
    size_t at = stageInsertPosition(chain, meta->stage);
    if (meta->stage == PostStage::Any)
        at = currentRow() >= 0 ? static_cast<size_t>(currentRow()) + 1 : chain.effects.size();
    auto* cmd = new AddEffectCommand(m_controller, at, makeEffect(meta->type));
    const size_t row = cmd->index();
    m_controller->undoStack()->push(cmd);
    setCurrentRow(static_cast<int>(row));
    return true;
}

void PostChainPanel::removeCurrent() {
    const int row = currentRow();
    if (row < 0)
        return;
    m_controller->undoStack()->push(
        new RemoveEffectCommand(m_controller, static_cast<size_t>(row)));
    setCurrentRow(std::min(row, m_model->rowCount() - 1));
}

void PostChainPanel::duplicateCurrent() {
    const int row = currentRow();
    if (row < 0)
        return;
    m_controller->undoStack()->push(
        new DuplicateEffectCommand(m_controller, static_cast<size_t>(row)));
    setCurrentRow(row + 1);
}

void PostChainPanel::moveCurrent(int delta) {
    const int row = currentRow();
    const int to = row + delta;
    if (row < 0 || to < 0 || to >= m_model->rowCount() || to == row)
        return;
    m_controller->undoStack()->push(
        new MoveEffectCommand(m_controller, static_cast<size_t>(row), static_cast<size_t>(to)));
    setCurrentRow(to);
}

bool PostChainPanel::loadPreset(const QString& path, QStringList* problems) {
    Problems found;
    std::optional<PostChainPreset> preset =
        loadPostChainFile(std::filesystem::path(path.toStdString()), found);
    if (!preset || found.hasErrors()) {
        if (problems) {
            problems->clear();
            for (const Problem& p : found.items)
                if (p.severity == Problem::Severity::Error)
                    *problems << QString::fromStdString(p.toString());
            if (problems->isEmpty())
                *problems << tr("%1: could not be read").arg(path);
        }
        return false;
    }
    if (preset->chain == m_controller->scene().post)
        return true;
    m_controller->undoStack()->push(
        new ReplacePostChainCommand(m_controller, m_controller->scene().post, preset->chain,
                                    tr("Load chain %1").arg(QString::fromStdString(preset->name))));
    return true;
}

bool PostChainPanel::savePreset(const QString& path, const QString& name, QString* error) {
    PostChainPreset preset;
    preset.name = name.toStdString();
    preset.chain = m_controller->scene().post;
    std::string message;
    if (savePostChainFile(preset, std::filesystem::path(path.toStdString()), &message))
        return true;
    if (error)
        *error = QString::fromStdString(message);
    return false;
}

void PostChainPanel::loadPresetDialog() {
    const QString dir = QString::fromStdString(resources::path("post-chains").string());
    const QString path = QFileDialog::getOpenFileName(this, tr("Load chain preset"), dir,
                                                      tr("Post chain presets (*.json)"));
    if (path.isEmpty())
        return;
    QStringList problems;
    if (loadPreset(path, &problems))
        return;
    emit problemsReported(
        tr("Could not load chain preset %1:\n%2").arg(path, problems.join(QLatin1Char('\n'))));
    QMessageBox box(QMessageBox::Warning, tr("Could not load %1").arg(QFileInfo(path).fileName()),
                    tr("%1 could not be loaded; the chain is unchanged.").arg(path),
                    QMessageBox::Ok, this);
    box.setInformativeText(problems.mid(0, 8).join(QLatin1Char('\n')));
    if (problems.size() > 8)
        box.setDetailedText(problems.join(QLatin1Char('\n')));
    box.exec();
}

void PostChainPanel::savePresetDialog() {
    QString path = QFileDialog::getSaveFileName(this, tr("Save chain preset"), QString(),
                                                tr("Post chain presets (*.json)"));
    if (path.isEmpty())
        return;
    if (QFileInfo(path).suffix().isEmpty())
        path += QStringLiteral(".json");
    QString error;
    if (savePreset(path, QFileInfo(path).completeBaseName(), &error))
        return;
    emit problemsReported(tr("Could not save chain preset %1: %2").arg(path, error));
    QMessageBox::warning(this, tr("Could not save %1").arg(QFileInfo(path).fileName()), error);
}

void PostChainPanel::updateActions() {
    const int row = currentRow();
    const int rows = m_model->rowCount();
    m_removeButton->setEnabled(row >= 0);
    m_duplicateButton->setEnabled(row >= 0);
    m_upButton->setEnabled(row > 0);
    m_downButton->setEnabled(row >= 0 && row + 1 < rows);
}

void PostChainPanel::updateIssues() {
    QStringList lines;
    for (int row = 0; row < m_model->rowCount(); ++row) {
        const QString issue = m_model->issue(row);
        if (!issue.isEmpty())
            lines << QStringLiteral("\u26a0 %1").arg(issue);
    }
    m_issueLabel->setText(lines.join(QLatin1Char('\n')));
    m_issueLabel->setVisible(!lines.isEmpty());
}

} // namespace velvet::ui
