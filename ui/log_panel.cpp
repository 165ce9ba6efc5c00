#include "ui/log_panel.h"

#include <QHBoxLayout>
#include <QPlainTextEdit>
#include <QTime>
#include <QToolButton>
#include <QVBoxLayout>

namespace velvet::ui {
namespace {

constexpr int kMaxRows = 5000; // a log left open for days must not grow without bound

const char* colourOf(LogPanel::Severity severity) {
    switch (severity) {
    case LogPanel::Severity::Info:
        return "palette(text)";
    case LogPanel::Severity::Warning:
        return "#c08020";
    case LogPanel::Severity::Error:
        return "#d04040";
    }
    return "palette(text)";
}

QString badgeOf(LogPanel::Severity severity) {
    switch (severity) {
    case LogPanel::Severity::Info:
        return QStringLiteral("info");
    case LogPanel::Severity::Warning:
        return QStringLiteral("warning");
    case LogPanel::Severity::Error:
        return QStringLiteral("error");
    }
    return {};
}

} // namespace

LogPanel::LogPanel(QWidget* parent) : QWidget(parent), m_view(new QPlainTextEdit(this)) {
    setObjectName(QStringLiteral("logPanel"));
    m_view->setObjectName(QStringLiteral("logView"));
    m_view->setReadOnly(true);
    m_view->setMaximumBlockCount(kMaxRows);
    m_view->setLineWrapMode(QPlainTextEdit::NoWrap);
    QFont mono = m_view->font();
    mono.setStyleHint(QFont::Monospace);
    mono.setFamily(QStringLiteral("monospace"));
    m_view->setFont(mono);

    auto* clearButton = new QToolButton(this);
    clearButton->setObjectName(QStringLiteral("logClear"));
    clearButton->setText(tr("Clear"));
    connect(clearButton, &QToolButton::clicked, this, &LogPanel::clear);

    auto* side = new QVBoxLayout;
    side->addWidget(clearButton);
    side->addStretch(1);
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(2, 2, 2, 2);
    layout->addWidget(m_view, 1);
    layout->addLayout(side);
}

void LogPanel::add(Severity severity, const QString& text) {
    m_entries.push_back({severity, text});
    const QStringList lines = text.split(QLatin1Char('\n'), Qt::SkipEmptyParts);
    const QString stamp = QTime::currentTime().toString(QStringLiteral("HH:mm:ss"));
    for (int i = 0; i < lines.size(); ++i) {
        const QString prefix =
            i == 0 ? QStringLiteral("%1 %2 ").arg(stamp, badgeOf(severity).leftJustified(8))
                   : QString(18, QLatin1Char(' '));
        m_view->appendHtml(
            QStringLiteral("<span style=\"color:%1; white-space:pre\">%2</span>")
                .arg(QLatin1String(colourOf(severity)), (prefix + lines[i]).toHtmlEscaped()));
    }
    emit messageAdded(severity, text);
}

QString LogPanel::text() const {
    return m_view->toPlainText();
}

void LogPanel::clear() {
    m_entries.clear();
    m_view->clear();
}

} // namespace velvet::ui
