#include "ui/texture_file_watcher.h"

#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"

#include <QFileInfo>
#include <algorithm>

namespace velvet::ui {

TextureFileWatcher::TextureFileWatcher(QObject* parent) : QObject(parent) {
    m_timer.setInterval(kPollIntervalMs);
    connect(&m_timer, &QTimer::timeout, this, &TextureFileWatcher::poll);
}

TextureFileWatcher::Stamp TextureFileWatcher::stampOf(const QString& file) {
    const QFileInfo info(file);
    Stamp s;
    s.file = file;
    s.exists = info.exists();
    if (s.exists) {
        s.modified = info.lastModified();
        s.size = info.size();
    }
    return s;
}

void TextureFileWatcher::setScene(const Scene& scene) {
    QStringList files;
    for (int i = 0; i < kTextureSlotCount; ++i) {
        const TextureRef& ref = scene.material.texture(static_cast<TextureSlot>(i));
        if (!ref.empty())
            files.push_back(QString::fromStdString(ref.file));
    }
    // The HDRI (the renderer stats it every frame) and the image-texture nodes of the material
    // graph (the renderer polls their files too).
    if (!scene.environment.hdri.empty())
        files.push_back(QString::fromStdString(scene.environment.hdri));
    if (const graph::Graph* g = scene.material.graph.get())
        for (const auto& [id, node] : g->nodes()) {
            if (!node.type || !node.type->samplesTexture)
                continue;
            const int file = node.type->settingIndex("file");
            if (file >= 0 && size_t(file) < node.settings.size() &&
                !node.settings[size_t(file)].empty())
                files.push_back(QString::fromStdString(node.settings[size_t(file)]));
        }
    files.removeDuplicates();
    if (files == this->files())
        return; // an edit that kept the files: keep their stamps (a change stays detectable)
    m_stamps.clear();
    for (const QString& file : files)
        m_stamps.push_back(stampOf(file));
    if (m_stamps.empty())
        m_timer.stop();
    else if (!m_timer.isActive())
        m_timer.start();
}

QStringList TextureFileWatcher::files() const {
    QStringList out;
    for (const Stamp& s : m_stamps)
        out.push_back(s.file);
    return out;
}

void TextureFileWatcher::poll() {
    bool any = false;
    for (Stamp& s : m_stamps) {
        Stamp now = stampOf(s.file);
        if (!(now == s)) {
            s = std::move(now);
            any = true;
        }
    }
    if (any)
        emit changed();
}

} // namespace velvet::ui
