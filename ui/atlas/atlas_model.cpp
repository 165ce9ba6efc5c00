#include "ui/atlas/atlas_model.h"

#include "ui/commands/atlas_commands.h"

#include <QDir>
#include <QFileInfo>
#include <QStandardPaths>
#include <QUndoStack>
#include <QUuid>
#include <algorithm>
#include <atomic>

namespace velvet::ui {

AtlasModel::AtlasModel(QUndoStack* undoStack, QObject* parent)
    : QObject(parent), m_undoStack(undoStack) {}

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

void AtlasModel::compose(AtlasDocument& atlas) {
    if (atlas.entries.empty() || atlas.width <= 0 || atlas.height <= 0) {
        atlas.image = Image();
        return;
    }
    Image image(atlas.width, atlas.height, 4);
    const int pad = std::max(0, atlas.padding);
    for (const AtlasEntry& e : atlas.entries) {
        const AtlasRegion& r = e.region;
        if (e.source.empty() || r.width <= 0 || r.height <= 0)
            continue;
        const int x0 = std::max(0, r.x - pad), x1 = std::min(atlas.width, r.x + r.width + pad);
        const int y0 = std::max(0, r.y - pad), y1 = std::min(atlas.height, r.y + r.height + pad);
        for (int y = y0; y < y1; ++y) {
            // Nearest source texel; outside the region the clamp replicates the edge (padding).
            const int ly = std::clamp(y - r.y, 0, r.height - 1);
            const int sy = std::min(e.source.height - 1, ly * e.source.height / r.height);
            for (int x = x0; x < x1; ++x) {
                const int lx = std::clamp(x - r.x, 0, r.width - 1);
                const int sx = std::min(e.source.width - 1, lx * e.source.width / r.width);
                const glm::vec4 c = e.source.rgba(sx, sy);
                float* out = image.at(x, y);
                out[0] = c.r, out[1] = c.g, out[2] = c.b, out[3] = c.a;
            }
        }
    }
    atlas.image = std::move(image);
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
    m_undoStack->push(new ReplaceAtlasCommand(
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
        e.name = QFileInfo(file).fileName();
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
    m_undoStack->push(new ReplaceAtlasCommand(this, kind, atlas(kind), std::move(next),
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
    m_undoStack->push(new SetAtlasRegionCommand(this, kind, index, old, region, mergeKey));
}

void AtlasModel::setAtlas(AtlasKind kind, AtlasDocument atlas) {
    m_atlases[size_t(kind)] = std::move(atlas);
    emit atlasChanged(kind);
}

void AtlasModel::setRegion(AtlasKind kind, int index, AtlasRegion region) {
    AtlasDocument& a = m_atlases[size_t(kind)];
    if (index < 0 || index >= int(a.entries.size()))
        return;
    a.entries[size_t(index)].region = region;
    compose(a);
    emit atlasChanged(kind);
}

bool AtlasModel::exportAtlas(AtlasKind kind, const QString& path, QString* error) {
    const AtlasDocument& a = atlas(kind);
    if (a.image.empty()) {
        if (error)
            *error = tr("The %1 atlas is empty").arg(kindLabel(kind));
        return false;
    }
    const QString suffix = QFileInfo(path).suffix().toLower();
    const PixelFormat format = suffix == QLatin1String("exr") ? PixelFormat::Half
                               : kind == AtlasKind::Albedo    ? PixelFormat::UInt8
                                                              : PixelFormat::UInt16;
    std::string message;
    if (!writeImage(path.toStdString(), a.image, format, &message)) { // atomic (core/image.h)
        if (error)
            *error = QString::fromStdString(message);
        return false;
    }
    m_atlases[size_t(kind)].filePath = QFileInfo(path).absoluteFilePath();
    return true;
}

QString AtlasModel::ensureFile(AtlasKind kind, QString* error) {
    if (!atlas(kind).filePath.isEmpty())
        return atlas(kind).filePath;
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
    return atlas(kind).filePath;
}

} // namespace velvet::ui
