#pragma once
/// @file autosave.h
/// Autosave and crash recovery (DESIGN.md, "Data safety"). While the document is dirty it is
/// written every interval (60 s by default) to QStandardPaths::AppDataLocation/autosave/,
/// atomically (core saveSceneFile: temp file + rename). The window removes the autosave after a
/// save and a clean close; replacing the document (new, open) removes the old one's. Beside each
/// autosave a one-line "NAME.autosave.json.source" names the document it belongs to, so a plain
/// start can list every recoverable autosave with its document and time (recoverable(),
/// offerStartupRecovery(), issue 17 item 11). When a file is opened, an autosave newer than the
/// file is offered for recovery; the recovered document is dirty until saved. An autosave is the
/// backup itself: it keeps no "*.bak" (core's atomic write does for documents), and a clean exit
/// removes any "*.autosave.json.bak" an earlier version left in the folder.
///
/// Issue 18, "Seconds, not a minute": besides the periodic timer, an autosave is written about
/// 2 s after the last edit of a burst (kDefaultDebounceMs; every undo-stack change and atlas edit
/// restarts it), so a kill loses at most the last ~2 s of work. The document is copied on the UI
/// thread (a copy, no serialisation) and turned into JSON and written on a worker thread, so a
/// large scene does not stall a frame. The atlases are in it: "NAME.autosave.atlas.json" with its
/// in-memory sources as EXR beside it, named by the autosave's `atlases` key.

#include <QDateTime>
#include <QList>
#include <QObject>
#include <QString>
#include <QThreadPool>
#include <functional>
#include <optional>

class QTimer;
class QWidget;

namespace velvet::ui {

class DocumentController;

class Autosave : public QObject {
    Q_OBJECT
public:
    static constexpr int kDefaultIntervalMs = 60000;
    /// Quiet time after the last edit before an autosave is written (VELVET_AUTOSAVE_DEBOUNCE_MS
    /// overrides it, for tests).
    static constexpr int kDefaultDebounceMs = 2000;

    /// An autosave that may be recovered: its file, the document it belongs to (absolute; empty
    /// for an untitled document) and when it was written.
    struct Recoverable {
        QString autosaveFile;
        QString documentPath;
        QDateTime written;
    };

    explicit Autosave(DocumentController* controller, QObject* parent = nullptr);
    ~Autosave() override;

    void setInterval(int ms);
    int interval() const;
    void setDebounce(int ms);
    int debounce() const;
    /// Writes the document's autosave on a worker thread when it is dirty (what the timers do);
    /// saved() or failed() follow on this thread. A request while one is running runs after it.
    void saveInBackground();
    /// Waits for a background write in progress (tests; before a synchronous write).
    void waitForBackground();
    /// The folder autosaves go to (created on the first write).
    static QString directory();
    /// The autosave file of the document at @p filePath (empty: the untitled document).
    static QString autosavePathFor(const QString& filePath);
    /// The autosave that may be recovered for @p filePath: it exists and, for a file, is newer
    /// than the file (or the file is gone). Empty when there is none.
    static QString recoverableFor(const QString& filePath);
    /// Every recoverable autosave in directory() (by recoverableFor's rule), newest first, except
    /// the one the current document writes.
    QList<Recoverable> recoverable() const;

    /// Writes the document's autosave now when it is dirty. False + @p error when the write
    /// failed; true when written or when there was nothing to write.
    bool saveNow(QString* error = nullptr);
    /// Removes the current document's autosave (after a save, or a clean close).
    void discard();
    /// A clean exit: discard(); every "*.autosave.json.bak" left in the folder, and every
    /// autosave whose document was saved after it (stale), is removed.
    void finish();
    /// Removes @p autosaveFile with the files kept beside it (".source", ".bak").
    static void remove(const QString& autosaveFile);
    /// Loads @p autosaveFile as the document of @p filePath with unsaved changes (the autosave
    /// stays until the document is saved). False + @p error when it could not be read.
    bool recover(const QString& autosaveFile, const QString& filePath, QString* error);
    /// Offers the recoverable autosave of @p filePath through the prompt (a message box by
    /// default) and recovers it when accepted, removes it when declined. True when recovered.
    bool offerRecovery(const QString& filePath);
    /// Replaces the question asked before recovering (tests answer without a dialog). The
    /// function gets the autosave's path and time and returns true to recover.
    void setPrompt(std::function<bool(const QString&, const QDateTime&)> prompt);
    /// Replaces offerStartupRecovery()'s RecoveryDialog (tests): given every recoverable
    /// autosave, newest first, returns the one to recover or nothing.
    void
    setStartupChooser(std::function<std::optional<Recoverable>(const QList<Recoverable>&)> chooser);
    /// At a plain start (no FILE): lists recoverable() in a RecoveryDialog over @p parent, where
    /// the artist recovers one (it becomes the document), discards any, or keeps them for later.
    /// True when one was recovered; false at once when there is nothing to offer.
    bool offerStartupRecovery(QWidget* parent);

signals:
    /// An autosave was written to @p path.
    void saved(const QString& path);
    void failed(const QString& message);

private:
    struct Snapshot;
    Snapshot snapshot() const;
    /// Writes @p snap (any thread). Empty on success, else the message.
    static QString write(Snapshot& snap);
    void finished(const QString& path, const QString& error);

    DocumentController* m_controller;
    QTimer* m_timer;
    QTimer* m_debounce;
    QThreadPool m_pool;     ///< one worker: autosaves are written one at a time
    bool m_running = false; ///< a background write is in progress
    bool m_pending = false; ///< another was asked for meanwhile
    QString m_lastPath;     ///< the autosave the current document last wrote
    std::function<bool(const QString&, const QDateTime&)> m_prompt;
    std::function<std::optional<Recoverable>(const QList<Recoverable>&)> m_startupChooser;
};

} // namespace velvet::ui
