#pragma once
/// @file log_panel.h
/// The Log dock: messages with a severity and a time, newest last. Scene problems reported by the
/// renderer, open/save problems and shader compile errors (file:line and the driver's message)
/// land here, so the viewport never needs a modal box to say what went wrong.

#include <QString>
#include <QStringList>
#include <QWidget>
#include <vector>

class QPlainTextEdit;

namespace velvet::ui {

class LogPanel : public QWidget {
    Q_OBJECT
public:
    enum class Severity { Info, Warning, Error };

    struct Entry {
        Severity severity;
        QString text;
    };

    explicit LogPanel(QWidget* parent = nullptr);

    /// Appends @p text (may span lines: each line becomes its own row, the first with the badge).
    void add(Severity severity, const QString& text);
    void info(const QString& text) { add(Severity::Info, text); }
    void warning(const QString& text) { add(Severity::Warning, text); }
    void error(const QString& text) { add(Severity::Error, text); }
    /// Every message so far (one entry per add), for tests and copying.
    const std::vector<Entry>& entries() const { return m_entries; }
    /// All messages as plain text, one line per row.
    QString text() const;
    void clear();

signals:
    /// A message was added (the main window may raise the dock on errors).
    void messageAdded(velvet::ui::LogPanel::Severity severity, const QString& text);

private:
    QPlainTextEdit* m_view;
    std::vector<Entry> m_entries;
};

} // namespace velvet::ui
