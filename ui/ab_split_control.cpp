#include "ui/ab_split_control.h"

#include "core/document_io.h"
#include "core/resources.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"
#include "ui/viewport_widget.h"

#include <QAction>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFontMetrics>
#include <QMenu>
#include <QSignalBlocker>
#include <QToolButton>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), qsizetype(s.size()));
}

/// The toolbar button's text stays short; the tooltip has all of it.
constexpr int kButtonTextChars = 24;

} // namespace

AbSplitControl::AbSplitControl(QWidget* window, DocumentController* controller,
                               ViewportWidget* viewport, LogPanel* log)
    : QObject(window), m_window(window), m_controller(controller), m_viewport(viewport),
      m_log(log) {
    m_action = new QAction(tr("A/B"), this);
    m_action->setObjectName(QStringLiteral("abSplitAction"));
    m_action->setCheckable(true);
    connect(m_action, &QAction::toggled, this, [this](bool on) { setSplit(on); });

    auto* menu = new QMenu(window);
    menu->setObjectName(QStringLiteral("abSplitMenu"));
    menu->addAction(tr("B = snapshot of the current material"), this, [this] {
        setSplit(false);
        setSplit(true);
    });
    // Comparing BRDF terms as the seed documents did: B is A with one term switched (GGX
    // beside Beckmann, Lambert beside Burley, …); everything else stays A's.
    QMenu* termMenu = menu->addMenu(tr("B = A with another BRDF term"));
    termMenu->setObjectName(QStringLiteral("abTermMenu"));
    for (ParamId id : {ParamId::Distribution, ParamId::Visibility, ParamId::Fresnel,
                       ParamId::Diffuse, ParamId::SheenModel}) {
        const ParamMeta& meta = paramMeta(id);
        QMenu* sub = termMenu->addMenu(fromView(meta.label));
        for (size_t i = 0; i < meta.choices.size(); ++i)
            sub->addAction(fromView(meta.choices[i]), this,
                           [this, id, i] { setSplitTerm(id, int(i)); });
    }
    QAction* preset = menu->addAction(tr("B from preset…"), this, &AbSplitControl::choosePreset);
    preset->setObjectName(QStringLiteral("abPresetAction"));
    menu->addSeparator();
    // X, like a viewer's "swap": the window's shortcut, so it works with the GL window focused.
    m_swap = new QAction(tr("Swap sides"), this);
    m_swap->setObjectName(QStringLiteral("abSwapAction"));
    m_swap->setShortcut(QKeySequence(Qt::Key_X));
    m_swap->setShortcutContext(Qt::WindowShortcut);
    m_swap->setEnabled(false);
    connect(m_swap, &QAction::triggered, this, [this] {
        m_viewport->setSplitSwapped(!m_viewport->splitSwapped());
        emit status(m_viewport->splitSwapped() ? tr("A/B split: B left, A right")
                                               : tr("A/B split: A left, B right"));
    });
    menu->addAction(m_swap);
    window->addAction(m_swap);

    m_button = new QToolButton(window);
    m_button->setObjectName(QStringLiteral("abSplitButton"));
    m_button->setDefaultAction(m_action);
    m_button->setMenu(menu);
    m_button->setPopupMode(QToolButton::MenuButtonPopup);
    showDescription();
}

QString AbSplitControl::presetFolder() {
    return QDir::cleanPath(QString::fromStdString(resources::path("presets").string()));
}

void AbSplitControl::setSplit(bool on, std::optional<Material> b, const QString& description) {
    if (on && !b) {
        b = m_controller->material(); // the snapshot B
        m_description = description.isEmpty() ? tr("snapshot of A") : description;
    } else if (on) {
        m_description = description.isEmpty() ? tr("another material") : description;
    } else {
        m_description.clear();
    }
    m_viewport->setSplitMaterial(on ? std::move(b) : std::nullopt);
    m_viewport->setSplitLabel(m_description);
    if (!on)
        m_viewport->setSplitSwapped(false);
    m_swap->setEnabled(on);
    {
        const QSignalBlocker block(m_action);
        m_action->setChecked(on);
    }
    showDescription();
    if (on)
        emit status(tr("A/B split: left the current material, right B (%1); drag the divider, "
                       "X swaps the sides")
                        .arg(m_description));
}

void AbSplitControl::setSplitTerm(ParamId term, int choice) {
    Material b = m_controller->material();
    b.setChoice(term, choice);
    const ParamMeta& meta = paramMeta(term);
    const QString name = fromView(meta.choices[size_t(b.choice(term))]);
    setSplit(true, b, tr("A with %1").arg(name));
    m_log->info(tr("A/B split: B is A with %1 %2").arg(fromView(meta.label), name));
}

bool AbSplitControl::setSplitPreset(const QString& path) {
    Problems problems;
    std::optional<Material> material = loadMaterialFile(path.toStdString(), problems);
    if (!material || problems.hasErrors()) {
        m_log->error(tr("Could not read the preset %1 for B").arg(path));
        return false;
    }
    setSplit(true, std::move(material), QFileInfo(path).completeBaseName());
    m_log->info(tr("A/B split: B is %1").arg(path));
    return true;
}

void AbSplitControl::choosePreset() {
    // The Library's presets, not the working folder: that is where materials to compare live.
    const QString path = QFileDialog::getOpenFileName(
        m_window, tr("Material preset for B"), presetFolder(), tr("Velvet presets (*.json)"));
    if (!path.isEmpty())
        setSplitPreset(path);
}

void AbSplitControl::showDescription() {
    if (m_description.isEmpty()) {
        m_action->setText(tr("A/B"));
        m_action->setToolTip(tr("A/B split: the current material (left) beside a snapshot taken "
                                "now or a preset (right)"));
        return;
    }
    const QString shortName = m_description.size() > kButtonTextChars
                                  ? m_description.left(kButtonTextChars - 1) + QChar(0x2026)
                                  : m_description;
    m_action->setText(tr("A/B · B: %1").arg(shortName));
    m_action->setToolTip(tr("A/B split: left A, the current material; right B, %1. Drag the "
                            "divider to move it; X swaps the sides.")
                             .arg(m_description));
}

} // namespace velvet::ui
