#include "ui/library/library_panel.h"

#include "core/document_io.h"
#include "core/resources.h"
#include "ui/commands/apply_preset_command.h"
#include "ui/document_controller.h"
#include "ui/library/thumbnail_renderer.h"

#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QListView>
#include <QMessageBox>
#include <QMimeData>
#include <QPainter>
#include <QPushButton>
#include <QRegularExpression>
#include <QSortFilterProxyModel>
#include <QStandardItemModel>
#include <QStandardPaths>
#include <QUndoStack>
#include <QUrl>
#include <QVBoxLayout>

namespace velvet::ui {
namespace {

/// Fabrics first (Velvet's reason to exist), then leather and the other organics, then paints
/// and coatings, metals, and everything else; by name within a group.
QString sortKey(const QString& name, const QStringList& tags) {
    static const QStringList groups = {QStringLiteral("fabric"), QStringLiteral("leather"),
                                       QStringLiteral("paint"), QStringLiteral("metal")};
    qsizetype group = groups.size();
    for (qsizetype g = 0; g < groups.size(); ++g)
        if (tags.contains(groups[g], Qt::CaseInsensitive)) {
            group = g;
            break;
        }
    return QString::number(group) + QLatin1Char(' ') + name;
}

QIcon makePlaceholder() {
    const int size = ThumbnailRenderer::kSize;
    QPixmap pixmap(size, size);
    pixmap.fill(QColor(60, 60, 64));
    QPainter painter(&pixmap);
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(90, 90, 96));
    painter.drawEllipse(QRectF(size * 0.2, size * 0.2, size * 0.6, size * 0.6));
    painter.end();
    return QIcon(pixmap);
}

/// A file name from a preset name: lower case, runs of other characters become '_'.
QString fileNameFor(const QString& name) {
    QString base = name.toLower();
    base.replace(QRegularExpression(QStringLiteral("[^a-z0-9]+")), QStringLiteral("_"));
    base = base.mid(base.startsWith(QLatin1Char('_')) ? 1 : 0);
    if (base.endsWith(QLatin1Char('_')))
        base.chop(1);
    return base.isEmpty() ? QStringLiteral("preset") : base;
}

/// The grid's model as a drag source: a preset leaves as its file's URL, so a drop on the
/// viewport (or any window that takes files) applies it like a file from a file manager.
class PresetDragModel final : public QSortFilterProxyModel {
public:
    using QSortFilterProxyModel::QSortFilterProxyModel;
    QStringList mimeTypes() const override { return {QStringLiteral("text/uri-list")}; }
    Qt::DropActions supportedDragActions() const override { return Qt::CopyAction; }
    QMimeData* mimeData(const QModelIndexList& indexes) const override {
        QList<QUrl> urls;
        for (const QModelIndex& index : indexes)
            if (index.isValid())
                urls << QUrl::fromLocalFile(index.data(LibraryPanel::PathRole).toString());
        if (urls.isEmpty())
            return nullptr;
        auto* mime = new QMimeData;
        mime->setUrls(urls);
        return mime;
    }
};

} // namespace

LibraryPanel::LibraryPanel(DocumentController* controller, QWidget* parent)
    : LibraryPanel(controller, Options{}, parent) {}

LibraryPanel::LibraryPanel(DocumentController* controller, const Options& options, QWidget* parent)
    : QWidget(parent), m_controller(controller) {
    init(options);
}

LibraryPanel::~LibraryPanel() = default;

void LibraryPanel::init(const Options& options) {
    setObjectName(QStringLiteral("libraryPanel"));
    m_presetDirs = options.presetDirs;
    if (m_presetDirs.isEmpty())
        m_presetDirs << QString::fromStdString(resources::path("presets").string());
    m_userDir = options.userDir;
    if (m_userDir.isEmpty())
        m_userDir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
                    QStringLiteral("/presets");
    m_placeholder = makePlaceholder();
    m_thumbnails = new ThumbnailRenderer(options.cacheDir, this);
    connect(m_thumbnails, &ThumbnailRenderer::thumbnailReady, this, &LibraryPanel::onThumbnail);
    connect(m_thumbnails, &ThumbnailRenderer::thumbnailFailed, this,
            [this](const QString& path, const QString& error) {
                emit problemsReported(tr("No thumbnail for %1: %2").arg(path, error));
            });

    m_model = new QStandardItemModel(this);
    m_proxy = new PresetDragModel(this);
    m_proxy->setSourceModel(m_model);
    m_proxy->setFilterRole(SearchRole);
    m_proxy->setFilterCaseSensitivity(Qt::CaseInsensitive);
    m_proxy->setSortCaseSensitivity(Qt::CaseInsensitive);
    m_proxy->setSortRole(SortRole);

    m_search = new QLineEdit(this);
    m_search->setObjectName(QStringLiteral("librarySearch"));
    m_search->setPlaceholderText(tr("Search by name or tag"));
    m_search->setClearButtonEnabled(true);
    connect(m_search, &QLineEdit::textChanged, m_proxy,
            &QSortFilterProxyModel::setFilterFixedString);

    m_view = new QListView(this);
    m_view->setObjectName(QStringLiteral("libraryView"));
    m_view->setModel(m_proxy);
    m_view->setViewMode(QListView::IconMode);
    m_view->setIconSize(QSize(ThumbnailRenderer::kSize, ThumbnailRenderer::kSize));
    m_view->setGridSize(QSize(ThumbnailRenderer::kSize + 28, ThumbnailRenderer::kSize + 36));
    m_view->setResizeMode(QListView::Adjust);
    m_view->setMovement(QListView::Static); // (turns dragging off: on again, as a source only)
    m_view->setDragEnabled(true);
    m_view->setDragDropMode(QAbstractItemView::DragOnly);
    m_view->setDefaultDropAction(Qt::CopyAction);
    m_view->setUniformItemSizes(true);
    m_view->setWordWrap(true);
    m_view->setSelectionMode(QAbstractItemView::SingleSelection);
    m_view->setEditTriggers(QAbstractItemView::NoEditTriggers);
    connect(m_view, &QListView::doubleClicked, this, [this](const QModelIndex& index) {
        QString error;
        if (!applyPreset(index.data(PathRole).toString(), &error))
            emit problemsReported(error);
    });

    m_apply = new QPushButton(tr("Apply"), this);
    m_apply->setObjectName(QStringLiteral("libraryApply"));
    m_apply->setEnabled(false);
    connect(m_apply, &QPushButton::clicked, this, &LibraryPanel::applySelected);
    auto* save = new QPushButton(tr("Save current material as preset…"), this);
    save->setObjectName(QStringLiteral("librarySave"));
    connect(save, &QPushButton::clicked, this, &LibraryPanel::saveUserPresetDialog);
    connect(m_view->selectionModel(), &QItemSelectionModel::currentChanged, this,
            [this](const QModelIndex& current) { m_apply->setEnabled(current.isValid()); });

    auto* buttons = new QHBoxLayout;
    buttons->setContentsMargins(0, 0, 0, 0);
    buttons->addWidget(m_apply);
    buttons->addStretch(1);
    buttons->addWidget(save);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(m_search);
    layout->addWidget(m_view, 1);
    layout->addLayout(buttons);

    reload();
}

QStandardItem* LibraryPanel::addPresetItem(const QString& path, bool user) {
    Problems problems;
    const std::optional<Material> material =
        loadMaterialFile(std::filesystem::path(path.toStdString()), problems);
    if (!material || problems.hasErrors()) {
        QStringList lines;
        for (const Problem& p : problems.items)
            lines << QString::fromStdString(p.toString());
        emit problemsReported(
            tr("Library: skipped %1:\n%2").arg(path, lines.join(QLatin1Char('\n'))));
        return nullptr;
    }
    const QString name = QString::fromStdString(material->name);
    QStringList tags;
    for (const std::string& tag : material->tags)
        tags << QString::fromStdString(tag);
    auto* item = new QStandardItem(m_placeholder, name);
    item->setEditable(false);
    item->setData(path, PathRole);
    item->setData(tags, TagsRole);
    item->setData(name + QLatin1Char(' ') + tags.join(QLatin1Char(' ')) + QLatin1Char(' ') +
                      QFileInfo(path).completeBaseName(),
                  SearchRole);
    item->setData(user, UserPresetRole);
    item->setData(sortKey(name, tags), SortRole);
    item->setData(false, ThumbnailReadyRole);
    item->setToolTip(tags.isEmpty()
                         ? name
                         : tr("%1\nTags: %2").arg(name, tags.join(QStringLiteral(", "))) +
                               (user ? tr("\n(user preset)") : QString()));
    m_model->appendRow(item);
    if (m_thumbnailsActive)
        m_thumbnails->request(path);
    return item;
}

void LibraryPanel::reload() {
    m_model->clear();
    auto addDir = [this](const QString& dir, bool user) {
        const QFileInfoList files =
            QDir(dir).entryInfoList({QStringLiteral("*.json")}, QDir::Files, QDir::Name);
        for (const QFileInfo& info : files)
            addPresetItem(info.absoluteFilePath(), user);
    };
    for (const QString& dir : m_presetDirs)
        addDir(dir, false);
    addDir(m_userDir, true);
    m_proxy->sort(0);
}

void LibraryPanel::showEvent(QShowEvent* event) {
    QWidget::showEvent(event);
    if (!m_thumbnailsActive)
        requestThumbnails();
}

void LibraryPanel::requestThumbnails() {
    m_thumbnailsActive = true;
    for (int row = 0; row < m_model->rowCount(); ++row) {
        const QStandardItem* item = m_model->item(row);
        if (!item->data(ThumbnailReadyRole).toBool())
            m_thumbnails->request(item->data(PathRole).toString());
    }
}

int LibraryPanel::placeholderCount() const {
    int count = 0;
    for (int row = 0; row < m_model->rowCount(); ++row)
        if (!m_model->item(row)->data(ThumbnailReadyRole).toBool())
            ++count;
    return count;
}

int LibraryPanel::rowOfName(const QString& name) const {
    for (int row = 0; row < m_model->rowCount(); ++row)
        if (m_model->item(row)->text() == name)
            return row;
    return -1;
}

void LibraryPanel::onThumbnail(const QString& path, const QImage& image) {
    for (int row = 0; row < m_model->rowCount(); ++row) {
        QStandardItem* item = m_model->item(row);
        if (item->data(PathRole).toString() == path) {
            item->setIcon(QIcon(QPixmap::fromImage(image)));
            item->setData(true, ThumbnailReadyRole);
        }
    }
}

bool LibraryPanel::applyPreset(const QString& path, QString* error) {
    Problems problems;
    std::optional<Material> material =
        loadMaterialFile(std::filesystem::path(path.toStdString()), problems);
    if (!material || problems.hasErrors()) {
        if (error) {
            QStringList lines;
            for (const Problem& p : problems.items)
                lines << QString::fromStdString(p.toString());
            *error = tr("Could not apply %1:\n%2").arg(path, lines.join(QLatin1Char('\n')));
        }
        return false;
    }
    const std::string preset = QDir::cleanPath(QFileInfo(path).absoluteFilePath()).toStdString();
    if (*material == m_controller->scene().material &&
        preset == m_controller->scene().materialPreset)
        return true;
    m_controller->undoStack()->push(
        new ApplyPresetCommand(m_controller, std::move(*material), preset));
    return true;
}

void LibraryPanel::applySelected() {
    const QModelIndex index = m_view->currentIndex();
    if (!index.isValid())
        return;
    QString error;
    if (!applyPreset(index.data(PathRole).toString(), &error)) {
        emit problemsReported(error);
        QMessageBox::warning(this, tr("Could not apply the preset"), error);
    }
}

bool LibraryPanel::saveUserPreset(const QString& name, const QStringList& tags, QString* error) {
    const QString trimmed = name.trimmed();
    if (trimmed.isEmpty()) {
        if (error)
            *error = tr("A preset needs a name.");
        return false;
    }
    if (!QDir().mkpath(m_userDir)) {
        if (error)
            *error = tr("Cannot create %1").arg(m_userDir);
        return false;
    }
    Material material = m_controller->scene().material;
    material.name = trimmed.toStdString();
    material.tags.clear();
    for (const QString& tag : tags)
        if (!tag.trimmed().isEmpty())
            material.tags.push_back(tag.trimmed().toStdString());
    const QString path =
        m_userDir + QLatin1Char('/') + fileNameFor(trimmed) + QStringLiteral(".json");
    std::string message;
    if (!saveMaterialFile(material, std::filesystem::path(path.toStdString()), &message)) {
        if (error)
            *error = QString::fromStdString(message);
        return false;
    }
    // Replace the item of an overwritten preset, else add one.
    for (int row = 0; row < m_model->rowCount(); ++row)
        if (m_model->item(row)->data(PathRole).toString() == QFileInfo(path).absoluteFilePath()) {
            m_model->removeRow(row);
            break;
        }
    addPresetItem(QFileInfo(path).absoluteFilePath(), true);
    m_proxy->sort(0);
    return true;
}

void LibraryPanel::saveUserPresetDialog() {
    QDialog dialog(this);
    dialog.setWindowTitle(tr("Save material as preset"));
    auto* name =
        new QLineEdit(QString::fromStdString(m_controller->scene().material.name), &dialog);
    name->setObjectName(QStringLiteral("presetName"));
    QStringList currentTags;
    for (const std::string& tag : m_controller->scene().material.tags)
        currentTags << QString::fromStdString(tag);
    auto* tags = new QLineEdit(currentTags.join(QStringLiteral(", ")), &dialog);
    tags->setObjectName(QStringLiteral("presetTags"));
    tags->setPlaceholderText(tr("fabric, glossy, …"));
    auto* buttons =
        new QDialogButtonBox(QDialogButtonBox::Save | QDialogButtonBox::Cancel, &dialog);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    auto* form = new QFormLayout(&dialog);
    form->addRow(tr("Name"), name);
    form->addRow(tr("Tags"), tags);
    form->addRow(buttons);
    if (dialog.exec() != QDialog::Accepted)
        return;
    QStringList tagList =
        tags->text().split(QRegularExpression(QStringLiteral("[,;]")), Qt::SkipEmptyParts);
    QString error;
    if (!saveUserPreset(name->text(), tagList, &error)) {
        emit problemsReported(tr("Could not save the preset: %1").arg(error));
        QMessageBox::warning(this, tr("Could not save the preset"), error);
    }
}

} // namespace velvet::ui
