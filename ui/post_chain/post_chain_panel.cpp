#include "ui/post_chain/post_chain_panel.h"

#include "core/post_chain_io.h"
#include "core/post_effects.h"
#include "core/resources.h"
#include "ui/color_picking.h"
#include "ui/commands/post_chain_commands.h"
#include "ui/document_controller.h"
#include "ui/post_chain/post_chain_model.h"

#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDragMoveEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QSignalBlocker>
#include <QSlider>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

constexpr int kSliderSteps = 1000;

int nextGestureKey() {
    static int key = 0;
    return ++key;
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

/// The widgets of one effect parameter in the form.
struct PostChainPanel::ParamRow {
    const ParamMeta* meta = nullptr;
    QSlider* slider = nullptr;
    QDoubleSpinBox* spin = nullptr;
    QComboBox* combo = nullptr;
    QToolButton* swatch = nullptr;
    glm::vec3 value{0.0f};
    int gesture = 0;

    float sliderEnd() const {
        return (meta->softMax > meta->min && meta->softMax < meta->max) ? meta->softMax : meta->max;
    }
    int toSlider(float v) const {
        const float t = (v - meta->min) / (sliderEnd() - meta->min);
        return std::clamp(static_cast<int>(std::lround(t * kSliderSteps)), 0, kSliderSteps);
    }
    float fromSlider(int position) const {
        return meta->min + (sliderEnd() - meta->min) * static_cast<float>(position) / kSliderSteps;
    }
};

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
    buttons->addWidget(load);
    buttons->addWidget(save);

    m_issueLabel = new QLabel(this);
    m_issueLabel->setObjectName(QStringLiteral("postChainIssues"));
    m_issueLabel->setWordWrap(true);
    m_issueLabel->setTextFormat(Qt::PlainText);
    m_issueLabel->hide();

    m_paramBox = new QGroupBox(tr("Parameters"), this);
    m_paramBox->setObjectName(QStringLiteral("postChainParameters"));
    m_paramForm = new QFormLayout(m_paramBox);
    m_paramForm->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);

    auto* layout = new QVBoxLayout(this);
    layout->addLayout(buttons);
    layout->addWidget(m_list, 1);
    layout->addWidget(m_issueLabel);
    layout->addWidget(m_paramBox);

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
        syncForm();
    });
    connect(m_model, &QAbstractItemModel::modelReset, this, [this] {
        updateActions();
        syncForm();
    });
    connect(m_controller, &DocumentController::postChainChanged, this, [this] {
        updateIssues();
        updateActions();
        syncForm();
    });
    updateIssues();
    updateActions();
    syncForm();
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

void PostChainPanel::syncForm() {
    const int row = currentRow();
    const QString type =
        row >= 0 ? m_model->index(row).data(PostChainModel::TypeRole).toString() : QString();
    if (row != m_formRow || type != m_formType)
        rebuildForm();
    else
        refreshFormValues();
}

void PostChainPanel::rebuildForm() {
    m_paramRows.clear();
    while (m_paramForm->rowCount() > 0)
        m_paramForm->removeRow(0);
    m_formRow = currentRow();
    m_formType = m_formRow >= 0
                     ? m_model->index(m_formRow).data(PostChainModel::TypeRole).toString()
                     : QString();
    const EffectMeta* meta = findPostEffect(m_formType.toStdString());
    if (!meta) {
        m_paramBox->setTitle(tr("Parameters"));
        m_paramBox->setEnabled(false);
        return;
    }
    m_paramBox->setEnabled(true);
    m_paramBox->setTitle(tr("%1 parameters").arg(fromView(meta->label)));
    for (const ParamMeta& p : meta->params) {
        auto row = std::make_unique<ParamRow>();
        ParamRow* r = row.get();
        r->meta = &p;
        const QString id = fromView(p.id);
        const QString name = QStringLiteral("effectParam:") + id;
        const std::string stdId(p.id);
        auto* field = new QWidget(m_paramBox);
        field->setObjectName(name);
        field->setToolTip(fromView(p.tooltip));
        auto* h = new QHBoxLayout(field);
        h->setContentsMargins(0, 0, 0, 0);
        switch (p.type) {
        case ParamType::Float: {
            r->slider = new QSlider(Qt::Horizontal, field);
            r->slider->setObjectName(name + QStringLiteral("/slider"));
            r->slider->setRange(0, kSliderSteps);
            r->spin = new QDoubleSpinBox(field);
            r->spin->setObjectName(name + QStringLiteral("/spin"));
            r->spin->setRange(p.min, p.max);
            r->spin->setDecimals(p.max - p.min > 100.0f ? 1 : 3);
            r->spin->setSingleStep((r->sliderEnd() - p.min) / 100.0);
            r->spin->setKeyboardTracking(false);
            if (!p.unit.empty())
                r->spin->setSuffix(QLatin1Char(' ') + fromView(p.unit));
            h->addWidget(r->slider, 1);
            h->addWidget(r->spin);
            connect(r->slider, &QSlider::sliderPressed, this,
                    [r] { r->gesture = nextGestureKey(); });
            connect(r->slider, &QSlider::sliderReleased, this, [r] { r->gesture = 0; });
            connect(r->slider, &QSlider::valueChanged, this, [this, r, stdId](int position) {
                const int key = r->slider->isSliderDown() ? r->gesture : 0;
                editParam(stdId, {r->fromSlider(position)}, key);
            });
            connect(r->spin, &QDoubleSpinBox::valueChanged, this,
                    [this, stdId](double v) { editParam(stdId, {static_cast<float>(v)}, 0); });
            break;
        }
        case ParamType::Choice: {
            r->combo = new QComboBox(field);
            r->combo->setObjectName(name + QStringLiteral("/combo"));
            for (std::string_view choice : p.choices)
                r->combo->addItem(fromView(choice));
            h->addWidget(r->combo, 1);
            connect(r->combo, &QComboBox::currentIndexChanged, this,
                    [this, stdId](int index) { editParam(stdId, {static_cast<float>(index)}, 0); });
            break;
        }
        case ParamType::Color: {
            r->swatch = new QToolButton(field);
            r->swatch->setObjectName(name + QStringLiteral("/swatch"));
            r->swatch->setMinimumWidth(64);
            h->addWidget(r->swatch);
            h->addStretch(1);
            connect(r->swatch, &QToolButton::clicked, this, [this, r, stdId] {
                const PickerColorSpace srgb;
                const QColor picked =
                    QColorDialog::getColor(srgb.toQColor(r->value), this, fromView(r->meta->label));
                if (!picked.isValid())
                    return;
                const glm::vec3 linear = srgb.fromQColor(picked);
                editParam(stdId, {linear.x, linear.y, linear.z}, 0);
            });
            break;
        }
        }
        auto* label = new QLabel(fromView(p.label), m_paramBox);
        label->setToolTip(fromView(p.tooltip));
        m_paramForm->addRow(label, field);
        m_paramRows.push_back(std::move(row));
    }
    refreshFormValues();
}

void PostChainPanel::refreshFormValues() {
    const auto& effects = m_controller->scene().post.effects;
    if (m_formRow < 0 || m_formRow >= static_cast<int>(effects.size()))
        return;
    const EffectInstance& effect = effects[static_cast<size_t>(m_formRow)];
    m_refreshing = true;
    for (const auto& row : m_paramRows) {
        row->value = effectValue(effect, *row->meta);
        if (row->slider) {
            const QSignalBlocker b1(row->slider);
            const QSignalBlocker b2(row->spin);
            row->spin->setValue(row->value.x);
            if (!row->slider->isSliderDown())
                row->slider->setValue(row->toSlider(row->value.x));
        }
        if (row->combo) {
            const QSignalBlocker b(row->combo);
            row->combo->setCurrentIndex(static_cast<int>(row->value.x));
        }
        if (row->swatch) {
            const QColor c = PickerColorSpace().toQColor(row->value);
            row->swatch->setStyleSheet(
                QStringLiteral("background-color: %1;").arg(c.name(QColor::HexRgb)));
            row->swatch->setToolTip(QStringLiteral("linear (%1, %2, %3)")
                                        .arg(row->value.x, 0, 'f', 3)
                                        .arg(row->value.y, 0, 'f', 3)
                                        .arg(row->value.z, 0, 'f', 3));
        }
    }
    m_refreshing = false;
}

void PostChainPanel::editParam(const std::string& id, std::vector<float> value, int mergeKey) {
    if (m_refreshing || m_formRow < 0)
        return;
    const auto& effects = m_controller->scene().post.effects;
    if (m_formRow >= static_cast<int>(effects.size()))
        return;
    const EffectInstance& effect = effects[static_cast<size_t>(m_formRow)];
    const EffectMeta* meta = findPostEffect(effect.type);
    const ParamMeta* p = meta ? findEffectParam(*meta, id) : nullptr;
    if (!p)
        return;
    for (float& v : value)
        v = std::clamp(v, p->min, p->max);
    const glm::vec3 current = effectValue(effect, *p);
    const bool same = paramComponents(*p) == 3
                          ? value.size() == 3 && glm::vec3(value[0], value[1], value[2]) == current
                          : !value.empty() && value[0] == current.x;
    if (same)
        return;
    const auto it = effect.params.find(id);
    std::vector<float> old = it == effect.params.end() ? std::vector<float>{} : it->second;
    m_controller->undoStack()->push(
        new SetEffectParamCommand(m_controller, static_cast<size_t>(m_formRow), id, std::move(old),
                                  std::move(value), mergeKey));
}

} // namespace velvet::ui
