#include "ui/models/atlas_model.h"

#include "ui/commands/atlas_commands.h"
#include "ui/document_controller.h"

#include <QDir>
#include <QFileInfo>
#include <QStandardPaths>
#include <QUndoStack>
#include <QUuid>
#include <algorithm>
#include <atomic>

namespace velvet::ui {

AtlasModel::AtlasModel(DocumentController* controller, QObject* parent)
    : QObject(parent), m_controller(controller) {
    connect(controller, &DocumentController::atlasChanged, this, &AtlasModel::atlasChanged);
}

const AtlasDocument& AtlasModel::atlas(AtlasKind kind) const {
    return m_controller->atlases()[kind];
}

QUndoStack* AtlasModel::undoStack() const {
    return m_controller->undoStack();
}

QString AtlasModel::kindLabel(AtlasKind kind) {
    switch (kind) {
    case AtlasKind::Albedo:
        return tr("Albedo");
    case AtlasKind::Material:
        return tr("Material");
    case AtlasKind::Normal:
        return tr("Normal");
    }
    return {};
}

TextureSlot AtlasModel::defaultSlot(AtlasKind kind) {
    switch (kind) {
    case AtlasKind::Albedo:
        return TextureSlot::BaseColor;
    case AtlasKind::Material:
        return TextureSlot::SpecRoughMetal;
    case AtlasKind::Normal:
        return TextureSlot::Normal;
    }
    return TextureSlot::BaseColor;
}

int AtlasModel::nextMergeKey() {
    static std::atomic<int> key{0};
    return ++key;
}

bool AtlasModel::pack(AtlasDocument& atlas, QString* error) const {
    std::vector<AtlasItemSize> sizes;
    for (const AtlasEntry& e : atlas.entries)
        sizes.push_back({e.source.width, e.source.height});
    AtlasOptions options;
    options.padding = atlas.padding;
    AtlasLayout layout;
    std::string message;
    if (!planAtlas(sizes, options, layout, &message)) {
        if (error)
            *error = QString::fromStdString(message);
        return false;
    }
    atlas.width = layout.width;
    atlas.height = layout.height;
    for (size_t i = 0; i < atlas.entries.size(); ++i)
        atlas.entries[i].region = layout.regions[i];
    compose(atlas);
    return true;
}

bool AtlasModel::addImages(AtlasKind kind, std::vector<AtlasEntry> images, QString* error) {
    if (images.empty())
        return true;
    AtlasDocument next = atlas(kind);
    for (AtlasEntry& e : images)
        next.entries.push_back(std::move(e));
    if (!pack(next, error))
        return false;
    const int added = int(images.size());
    undoStack()->push(new ReplaceAtlasCommand(
        this, kind, atlas(kind), std::move(next),
        tr("Add %n image(s) to the %1 atlas", nullptr, added).arg(kindLabel(kind))));
    return true;
}

bool AtlasModel::addImageFiles(AtlasKind kind, const QStringList& files, QString* error) {
    std::vector<AtlasEntry> images;
    QStringList problems;
    for (const QString& file : files) {
        AtlasEntry e;
        std::string message;
        if (!readImage(file.toStdString(), e.source, &message)) {
            problems << QString::fromStdString(message);
            continue;
        }
        e.name = QFileInfo(file).fileName().toStdString();
        e.file = QDir::cleanPath(QFileInfo(file).absoluteFilePath()).toStdString();
        images.push_back(std::move(e));
    }
    QString packError;
    const bool ok = addImages(kind, std::move(images), &packError);
    if (!ok)
        problems << packError;
    if (error)
        *error = problems.join(QLatin1Char('\n'));
    return ok && problems.isEmpty();
}

bool AtlasModel::repack(AtlasKind kind, QString* error) {
    AtlasDocument next = atlas(kind);
    if (!pack(next, error))
        return false;
    undoStack()->push(new ReplaceAtlasCommand(this, kind, atlas(kind), std::move(next),
                                              tr("Repack the %1 atlas").arg(kindLabel(kind))));
    return true;
}

void AtlasModel::editRegion(AtlasKind kind, int index, AtlasRegion region, int mergeKey) {
    const AtlasDocument& a = atlas(kind);
    if (index < 0 || index >= int(a.entries.size()))
        return;
    region.width = std::clamp(region.width, 1, std::max(1, a.width));
    region.height = std::clamp(region.height, 1, std::max(1, a.height));
    region.x = std::clamp(region.x, 0, std::max(0, a.width - region.width));
    region.y = std::clamp(region.y, 0, std::max(0, a.height - region.height));
    const AtlasRegion old = a.entries[size_t(index)].region;
    if (region == old)
        return;
    undoStack()->push(new SetAtlasRegionCommand(this, kind, index, old, region, mergeKey));
}

void AtlasModel::setAtlas(AtlasKind kind, AtlasDocument atlas) {
    m_controller->setAtlas(kind, std::move(atlas));
}

void AtlasModel::setRegion(AtlasKind kind, int index, AtlasRegion region) {
    AtlasDocument a = atlas(kind);
    if (index < 0 || index >= int(a.entries.size()))
        return;
    a.entries[size_t(index)].region = region;
    compose(a);
    m_controller->setAtlas(kind, std::move(a));
}

bool AtlasModel::exportAtlas(AtlasKind kind, const QString& path, QString* error) {
    const AtlasDocument& a = atlas(kind);
    if (a.image.empty()) {
        if (error)
            *error = tr("The %1 atlas is empty").arg(kindLabel(kind));
        return false;
    }
    const PixelFormat format = atlasExportFormat(kind, QFileInfo(path).suffix().toStdString());
    std::string message;
    if (!writeImage(path.toStdString(), a.image, format, &message)) { // atomic (core/image.h)
        if (error)
            *error = QString::fromStdString(message);
        return false;
    }
    // Where it was exported is remembered (and saved), but is no edit of the atlas.
    AtlasDocument next = a;
    next.filePath = QDir::cleanPath(QFileInfo(path).absoluteFilePath()).toStdString();
    m_controller->setAtlas(kind, std::move(next));
    return true;
}

bool AtlasModel::exportMaterialAtlasPacked(PackLayout layout, const QString& path, QString* error) {
    const AtlasDocument& a = atlas(AtlasKind::Material);
    if (a.image.empty()) {
        if (error)
            *error = tr("The %1 atlas is empty").arg(kindLabel(AtlasKind::Material));
        return false;
    }
    ChannelMaps maps;
    Image packed;
    std::string message;
    if (!unpackChannels(PackLayout::SpecRoughMetal, a.image, maps, &message) ||
        !packChannels(layout, maps, packed, &message)) {
        if (error)
            *error = QString::fromStdString(message);
        return false;
    }
    const bool exr =
        QFileInfo(path).suffix().compare(QLatin1String("exr"), Qt::CaseInsensitive) == 0;
    if (!writeImage(path.toStdString(), packed, exr ? PixelFormat::Half : PixelFormat::UInt16,
                    &message)) { // atomic (core/image.h)
        if (error)
            *error = QString::fromStdString(message);
        return false;
    }
    return true;
}

bool AtlasModel::exportAll(const QString& folder, const QString& stem, const QString& extension,
                           QStringList* written, QString* error) {
    std::vector<std::filesystem::path> paths;
    std::string message;
    const bool ok =
        exportAtlasImages(m_controller->atlases(), folder.toStdString(), stem.toStdString(),
                          extension.toStdString(), &paths, &message);
    if (written)
        for (const std::filesystem::path& p : paths)
            *written << QString::fromStdString(p.string());
    if (!ok && error)
        *error = QString::fromStdString(message);
    return ok;
}

QString AtlasModel::ensureFile(AtlasKind kind, QString* error) {
    if (!atlas(kind).filePath.empty())
        return QString::fromStdString(atlas(kind).filePath);
    const QString dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
                        QStringLiteral("/atlases");
    if (!QDir().mkpath(dir)) {
        if (error)
            *error = tr("Could not create %1").arg(dir);
        return {};
    }
    const QString path = QStringLiteral("%1/%2-%3.png")
                             .arg(dir, kindLabel(kind).toLower(),
                                  QUuid::createUuid().toString(QUuid::WithoutBraces).left(8));
    if (!exportAtlas(kind, path, error))
        return {};
    return QString::fromStdString(atlas(kind).filePath);
}

} // namespace velvet::ui
