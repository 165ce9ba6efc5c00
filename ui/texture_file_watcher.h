#pragma once
/// @file texture_file_watcher.h
/// Live texture reload for an idle editor. The renderer re-uploads a texture whose file changed
/// at the start of each frame (Renderer::render polls core::TextureCache), but an idle viewport
/// draws no frames, so an image edited in another program would not show until something else
/// asked for one. This watcher stats the scene's texture files every 0.5 s, only while the
/// material uses any, and emits changed() when one's modification time or size moves (it also
/// sees files replaced by rename, as image editors save them, which a QFileSystemWatcher loses).

#include "core/scene.h"

#include <QDateTime>
#include <QObject>
#include <QString>
#include <QTimer>
#include <vector>

namespace velvet::ui {

class TextureFileWatcher : public QObject {
    Q_OBJECT
public:
    static constexpr int kPollIntervalMs = 500;

    explicit TextureFileWatcher(QObject* parent = nullptr);

    /// Watches the files @p scene's material texture slots, its graph's image-texture nodes and
    /// its HDRI name (the timer runs only when there is at least one).
    void setScene(const Scene& scene);
    /// The files watched now (tests).
    QStringList files() const;
    bool isPolling() const { return m_timer.isActive(); }

signals:
    /// A watched file's stamp changed (or it appeared or vanished): draw a frame.
    void changed();

private:
    struct Stamp {
        QString file;
        bool exists = false;
        QDateTime modified;
        qint64 size = -1;
        bool operator==(const Stamp&) const = default;
    };
    static Stamp stampOf(const QString& file);
    void poll();

    std::vector<Stamp> m_stamps;
    QTimer m_timer;
};

} // namespace velvet::ui
