#include "ui/autosave.h"

#include "core/atlas_document.h"
#include "core/atomic_file.h"
#include "core/document_io.h"
#include "ui/document_controller.h"
#include "ui/recovery_dialog.h"

#include <QApplication>
#include <QCryptographicHash>
#include <QDir>
#include <QFileInfo>
#include <QMessageBox>
#include <QSaveFile>
#include <QStandardPaths>
#include <QTimer>
#include <QUndoStack>
#include <algorithm>
#include <cstring>
#include <memory>

namespace velvet::ui {
namespace {

const QString kSourceSuffix = QStringLiteral(".source");
const QString kBackupSuffix = QStringLiteral(".bak");

/// The document an autosave belongs to, from the line beside it; empty for an untitled document
/// (or an autosave written before the line existed).
QString documentOf(const QString& autosaveFile) {
    QFile source(autosaveFile + kSourceSuffix);
    if (!source.open(QIODevice::ReadOnly))
        return {};
    return QString::fromUtf8(source.readAll()).trimmed();
}

/// "NAME.autosave.atlas.json" beside "NAME.autosave.json".
QString atlasFileOf(const QString& autosaveFile) {
    QString path = autosaveFile;
    path.chop(int(std::strlen(".json")));
    return path + QStringLiteral(".atlas.json");
}

} // namespace

/// What a background write needs, copied on the UI thread: no pointer into the document.
struct Autosave::Snapshot {
    Scene scene;
    AtlasSet atlases;
    QString path;     ///< the autosave file
    QString document; ///< the document it belongs to (absolute; empty: untitled)
};

Autosave::Autosave(DocumentController* controller, QObject* parent)
    : QObject(parent), m_controller(controller), m_timer(new QTimer(this)),
      m_debounce(new QTimer(this)) {
    m_pool.setMaxThreadCount(1);
    m_timer->setInterval(kDefaultIntervalMs);
    connect(m_timer, &QTimer::timeout, this, &Autosave::saveInBackground);
    m_timer->start();
    // The debounce: every edit (undo, redo included) restarts it; it fires after a quiet spell.
    const int debounceMs = qEnvironmentVariableIntValue("VELVET_AUTOSAVE_DEBOUNCE_MS");
    m_debounce->setSingleShot(true);
    m_debounce->setInterval(debounceMs > 0 ? debounceMs : kDefaultDebounceMs);
    connect(m_debounce, &QTimer::timeout, this, &Autosave::saveInBackground);
    auto restart = [this] {
        if (m_controller->isDirty())
            m_debounce->start();
    };
    connect(m_controller->undoStack(), &QUndoStack::indexChanged, this, restart);
    connect(m_controller, &DocumentController::atlasChanged, this, restart);
    // Another document (new, open, save as): the old autosave belongs to a state the artist
    // has saved or chosen to discard.
    connect(m_controller, &DocumentController::fileChanged, this, [this] {
        if (!m_lastPath.isEmpty())
            remove(m_lastPath);
        m_lastPath.clear();
    });
}

Autosave::~Autosave() {
    m_pool.waitForDone(); // the worker reports back to this object
}

void Autosave::setDebounce(int ms) {
    m_debounce->setInterval(std::max(1, ms));
}

int Autosave::debounce() const {
    return m_debounce->interval();
}

Autosave::Snapshot Autosave::snapshot() const {
    Snapshot snap;
    snap.scene = m_controller->scene();
    // Entries, sizes and sources, not the composed images: the atlas document does not store
    // them (loading composes them again), and copying them would double the UI thread's cost.
    const AtlasSet& atlases = m_controller->atlases();
    for (int k = 0; k < kAtlasKindCount; ++k) {
        const AtlasDocument& from = atlases[AtlasKind(k)];
        AtlasDocument& to = snap.atlases[AtlasKind(k)];
        to.entries = from.entries;
        to.width = from.width;
        to.height = from.height;
        to.padding = from.padding;
        to.filePath = from.filePath;
    }
    snap.path = autosavePathFor(m_controller->filePath());
    snap.document = m_controller->filePath().isEmpty()
                        ? QString()
                        : QFileInfo(m_controller->filePath()).absoluteFilePath();
    return snap;
}

QString Autosave::write(Snapshot& snap) {
    if (!QDir().mkpath(directory()))
        return tr("Could not create the autosave folder %1").arg(directory());
    std::string message;
    // The atlases first (their in-memory sources as EXR beside them), then the scene naming them,
    // as DocumentController::saveAs orders a save: a reader never sees a scene without its atlas.
    snap.scene.atlases.clear();
    if (!snap.atlases.empty()) {
        const std::filesystem::path atlasFile = atlasFileOf(snap.path).toStdString();
        if (!saveAtlasFile(snap.atlases, atlasFile, &message))
            return tr("Autosave failed: %1").arg(QString::fromStdString(message));
        snap.scene.atlases = atlasFile.generic_string();
    }
    // Atomic (core/atomic_file.h), no backup generations: an autosave is itself the backup.
    const std::filesystem::path file = snap.path.toStdString();
    if (!writeFileAtomically(file, sceneToJson(snap.scene, file.parent_path()), &message))
        return tr("Autosave failed: %1").arg(QString::fromStdString(message));
    // Which document this is, for the start-up list (the name holds only a hash of the path).
    if (documentOf(snap.path) != snap.document || !QFile::exists(snap.path + kSourceSuffix)) {
        QSaveFile source(snap.path + kSourceSuffix);
        if (!source.open(QIODevice::WriteOnly) || source.write(snap.document.toUtf8()) < 0 ||
            !source.commit())
            return tr("Autosave could not record its document in %1").arg(source.fileName());
    }
    return {};
}

void Autosave::saveInBackground() {
    if (!m_controller->isDirty())
        return;
    if (m_running) {
        m_pending = true;
        return;
    }
    m_running = true;
    auto snap = std::make_shared<Snapshot>(snapshot());
    m_pool.start([this, snap] {
        const QString error = write(*snap);
        QMetaObject::invokeMethod(
            this, [this, path = snap->path, error] { finished(path, error); },
            Qt::QueuedConnection);
    });
}

void Autosave::finished(const QString& path, const QString& error) {
    m_running = false;
    if (error.isEmpty()) {
        m_lastPath = path;
        emit saved(path);
    } else {
        emit failed(error);
    }
    if (m_pending) {
        m_pending = false;
        saveInBackground();
    }
}

void Autosave::waitForBackground() {
    m_pool.waitForDone();
    QCoreApplication::sendPostedEvents(this);
}

void Autosave::setInterval(int ms) {
    m_timer->start(std::max(1, ms));
}

int Autosave::interval() const {
    return m_timer->interval();
}

QString Autosave::directory() {
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
           QStringLiteral("/autosave");
}

QString Autosave::autosavePathFor(const QString& filePath) {
    if (filePath.isEmpty())
        return directory() + QStringLiteral("/untitled.autosave.json");
    const QString absolute = QFileInfo(filePath).absoluteFilePath();
    const QByteArray hash =
        QCryptographicHash::hash(absolute.toUtf8(), QCryptographicHash::Sha1).toHex().left(12);
    return QStringLiteral("%1/%2-%3.autosave.json")
        .arg(directory(), QFileInfo(filePath).completeBaseName(), QString::fromLatin1(hash));
}

QString Autosave::recoverableFor(const QString& filePath) {
    const QString path = autosavePathFor(filePath);
    const QFileInfo autosave(path);
    if (!autosave.exists())
        return {};
    if (!filePath.isEmpty()) {
        const QFileInfo file(filePath);
        if (file.exists() && file.lastModified() >= autosave.lastModified())
            return {};
    }
    return path;
}

bool Autosave::saveNow(QString* error) {
    waitForBackground();
    if (!m_controller->isDirty())
        return true;
    Snapshot snap = snapshot();
    const QString message = write(snap);
    if (!message.isEmpty()) {
        if (error)
            *error = message;
        return false;
    }
    m_lastPath = snap.path;
    emit saved(snap.path);
    return true;
}

void Autosave::discard() {
    remove(m_lastPath.isEmpty() ? autosavePathFor(m_controller->filePath()) : m_lastPath);
    m_lastPath.clear();
}

void Autosave::finish() {
    discard();
    const QDir dir(directory());
    // Backups an earlier version kept of autosaves, and record lines whose autosave is gone.
    for (const QString& name : dir.entryList({QStringLiteral("*.autosave.json") + kBackupSuffix,
                                              QStringLiteral("*.autosave.json") + kSourceSuffix},
                                             QDir::Files)) {
        const QString path = dir.filePath(name);
        if (name.endsWith(kBackupSuffix) || !QFile::exists(path.chopped(kSourceSuffix.size())))
            QFile::remove(path);
    }
    // Autosaves of documents saved since: recoverableFor never offers them again.
    for (const QFileInfo& file :
         dir.entryInfoList({QStringLiteral("*.autosave.json")}, QDir::Files)) {
        const QFileInfo saved(documentOf(file.absoluteFilePath()));
        if (!saved.filePath().isEmpty() && saved.exists() &&
            saved.lastModified() >= file.lastModified())
            remove(file.absoluteFilePath());
    }
}

void Autosave::remove(const QString& autosaveFile) {
    // The atlas document and its EXR sources ("NAME.autosave.<kind>-<n>.exr").
    QFile::remove(atlasFileOf(autosaveFile));
    const QFileInfo info(autosaveFile);
    QString stem = info.fileName();
    stem.chop(int(std::strlen(".json")));
    for (const QString& name :
         info.dir().entryList({stem + QStringLiteral(".*-*.exr")}, QDir::Files))
        QFile::remove(info.dir().filePath(name));
    QFile::remove(autosaveFile);
    QFile::remove(autosaveFile + kSourceSuffix);
    QFile::remove(autosaveFile + kBackupSuffix);
}

QList<Autosave::Recoverable> Autosave::recoverable() const {
    QList<Recoverable> found;
    const QDir dir(directory());
    const QString own = m_lastPath.isEmpty() ? QString() : QFileInfo(m_lastPath).absoluteFilePath();
    for (const QFileInfo& file :
         dir.entryInfoList({QStringLiteral("*.autosave.json")}, QDir::Files)) {
        const QString path = file.absoluteFilePath();
        if (path == own)
            continue;
        const QString document = documentOf(path);
        // recoverableFor's rule: stale when the document was saved after it was written.
        const QFileInfo saved(document);
        if (!document.isEmpty() && saved.exists() && saved.lastModified() >= file.lastModified())
            continue;
        found.push_back({path, document, file.lastModified()});
    }
    std::sort(found.begin(), found.end(),
              [](const Recoverable& a, const Recoverable& b) { return a.written > b.written; });
    return found;
}

bool Autosave::recover(const QString& autosaveFile, const QString& filePath, QString* error) {
    Problems problems;
    std::optional<Scene> scene = loadSceneFile(autosaveFile.toStdString(), problems);
    if (!scene || problems.hasErrors()) {
        if (error) {
            QStringList lines;
            for (const Problem& p : problems.items)
                lines << QString::fromStdString(p.toString());
            *error = lines.isEmpty() ? tr("%1 could not be read").arg(autosaveFile)
                                     : lines.join(QLatin1Char('\n'));
        }
        return false;
    }
    m_controller->setRecoveredDocument(
        std::move(*scene), filePath.isEmpty() ? QString() : QFileInfo(filePath).absoluteFilePath());
    // Atlas sources the autosave wrote live beside it and go when it is removed: back to
    // in-memory sources, so the document's next save writes them beside the document.
    const QString folder = QDir(directory()).absolutePath() + QLatin1Char('/');
    for (int k = 0; k < kAtlasKindCount; ++k) {
        AtlasDocument atlas = m_controller->atlases()[AtlasKind(k)];
        bool changed = false;
        for (AtlasEntry& entry : atlas.entries)
            if (QString::fromStdString(entry.file).startsWith(folder) && !entry.source.empty()) {
                entry.file.clear();
                changed = true;
            }
        if (changed)
            m_controller->setAtlas(AtlasKind(k), std::move(atlas));
    }
    // Keep it until the recovered document is saved or written again.
    m_lastPath = autosaveFile;
    return true;
}

bool Autosave::offerRecovery(const QString& filePath) {
    const QString autosave = recoverableFor(filePath);
    if (autosave.isEmpty())
        return false;
    const QDateTime when = QFileInfo(autosave).lastModified();
    bool accept = false;
    if (m_prompt) {
        accept = m_prompt(autosave, when);
    } else {
        const QString time = QLocale().toString(when, QLocale::ShortFormat);
        // An untitled document has no saved file to be newer than.
        const QString text =
            filePath.isEmpty()
                ? tr("Velvet found unsaved changes of an untitled document, autosaved %1. "
                     "Recover them?")
                      .arg(time)
                : tr("Velvet found an autosave of %1 from %2, newer than the saved file. "
                     "Recover it?")
                      .arg(QFileInfo(filePath).fileName(), time);
        accept = QMessageBox::question(QApplication::activeWindow(), tr("Recover unsaved changes?"),
                                       text, QMessageBox::Yes | QMessageBox::No,
                                       QMessageBox::Yes) == QMessageBox::Yes;
    }
    if (!accept) {
        remove(autosave);
        return false;
    }
    QString error;
    if (!recover(autosave, filePath, &error)) {
        emit failed(error);
        return false;
    }
    return true;
}

void Autosave::setStartupChooser(
    std::function<std::optional<Recoverable>(const QList<Recoverable>&)> chooser) {
    m_startupChooser = std::move(chooser);
}

void Autosave::setPrompt(std::function<bool(const QString&, const QDateTime&)> prompt) {
    m_prompt = std::move(prompt);
}

bool Autosave::offerStartupRecovery(QWidget* parent) {
    const QList<Recoverable> found = recoverable();
    if (found.isEmpty())
        return false;
    std::optional<Recoverable> chosen;
    if (m_startupChooser) {
        chosen = m_startupChooser(found);
    } else {
        RecoveryDialog dialog(found, parent);
        const bool accepted = dialog.exec() == QDialog::Accepted;
        for (const QString& file : dialog.discarded())
            remove(file);
        // "Later" (or none chosen): what is left stays for the next start or the file's next open.
        if (accepted)
            chosen = dialog.chosen();
    }
    if (!chosen)
        return false;
    QString error;
    if (!recover(chosen->autosaveFile, chosen->documentPath, &error)) {
        emit failed(error);
        return false;
    }
    return true;
}

} // namespace velvet::ui
