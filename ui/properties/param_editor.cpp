#include "ui/properties/param_editor.h"

#include "ui/properties/choice_param_editor.h"
#include "ui/properties/color_param_editor.h"
#include "ui/properties/float_param_editor.h"

#include <QAction>
#include <QToolButton>

namespace velvet::ui {

ParamEditor* ParamEditor::create(ParamId id, QWidget* parent) {
    switch (paramMeta(id).type) {
    case ParamType::Float:
        return new FloatParamEditor(id, parent);
    case ParamType::Color:
        return new ColorParamEditor(id, parent);
    case ParamType::Choice:
        return new ChoiceParamEditor(id, parent);
    }
    return nullptr;
}

ParamEditor::ParamEditor(ParamId id, QWidget* parent) : QWidget(parent), m_param(id) {
    setObjectName(QStringLiteral("param:") + QString::fromUtf8(meta().id));
    setToolTip(QString::fromUtf8(meta().tooltip));
    auto* reset = new QAction(tr("Reset %1").arg(QString::fromUtf8(meta().label)), this);
    connect(reset, &QAction::triggered, this, [this] { emit resetRequested(m_param); });
    addAction(reset);
    setContextMenuPolicy(Qt::ActionsContextMenu);
}

QToolButton* ParamEditor::makeResetButton() {
    auto* button = new QToolButton(this);
    button->setObjectName(partName("reset"));
    button->setText(QStringLiteral("\u21ba"));
    button->setAutoRaise(true);
    button->setFocusPolicy(Qt::NoFocus);
    button->setToolTip(tr("Reset to the default"));
    connect(button, &QToolButton::clicked, this, [this] { emit resetRequested(m_param); });
    return button;
}

QString ParamEditor::partName(const char* part) const {
    return objectName() + QLatin1Char('/') + QLatin1String(part);
}

int ParamEditor::nextGestureKey() {
    static int last = 0;
    return ++last;
}

} // namespace velvet::ui
