#include "ui/autosave.h"

#include "core/document_io.h"
#include "ui/document_controller.h"

#include <QApplication>
#include <QCryptographicHash>
#include <QDir>
#include <QFileInfo>
#include <QMessageBox>
#include <QStandardPaths>
#include <QTimer>

namespace velvet::ui {

Autosave::Autosave(DocumentController* controller, QObject* parent)
    : QObject(parent), m_controller(controller), m_timer(new QTimer(this)) {
    m_timer->setInterval(kDefaultIntervalMs);
    connect(m_timer, &QTimer::timeout, this, [this] {
        QString error;
        if (!saveNow(&error))
            emit failed(error);
    });
    m_timer->start();
    // Another document (new, open, save as): the old autosave belongs to a state the artist
    // has saved or chosen to discard.
    connect(m_controller, &DocumentController::fileChanged, this, [this] {
        if (!m_lastPath.isEmpty())
            QFile::remove(m_lastPath);
        m_lastPath.clear();
    });
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
    if (!m_controller->isDirty())
        return true;
    const QString path = autosavePathFor(m_controller->filePath());
    if (!QDir().mkpath(directory())) {
        if (error)
            *error = tr("Could not create the autosave folder %1").arg(directory());
        return false;
    }
    std::string message;
    // Atomic: a temp file beside the target, then a rename (core/atomic_file.h).
    if (!saveSceneFile(m_controller->scene(), path.toStdString(), &message)) {
        if (error)
            *error = tr("Autosave failed: %1").arg(QString::fromStdString(message));
        return false;
    }
    m_lastPath = path;
    emit saved(path);
    return true;
}

void Autosave::discard() {
    const QString path =
        m_lastPath.isEmpty() ? autosavePathFor(m_controller->filePath()) : m_lastPath;
    QFile::remove(path);
    m_lastPath.clear();
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
        const QString name =
            filePath.isEmpty() ? tr("an untitled document") : QFileInfo(filePath).fileName();
        accept = QMessageBox::question(
                     QApplication::activeWindow(), tr("Recover unsaved changes?"),
                     tr("Velvet found an autosave of %1 from %2, newer than the saved file. "
                        "Recover it?")
                         .arg(name, QLocale().toString(when, QLocale::ShortFormat)),
                     QMessageBox::Yes | QMessageBox::No, QMessageBox::Yes) == QMessageBox::Yes;
    }
    if (!accept) {
        QFile::remove(autosave);
        return false;
    }
    QString error;
    if (!recover(autosave, filePath, &error)) {
        emit failed(error);
        return false;
    }
    return true;
}

void Autosave::setPrompt(std::function<bool(const QString&, const QDateTime&)> prompt) {
    m_prompt = std::move(prompt);
}

} // namespace velvet::ui
