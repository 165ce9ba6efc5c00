#include "ui/properties/uv_transform_editor.h"

#include "ui/document_controller.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QToolButton>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

} // namespace

UvTransformEditor::UvTransformEditor(DocumentController* controller, TextureSlot slot,
                                     const QString& namePrefix, QWidget* parent)
    : QWidget(parent), m_controller(controller), m_slot(slot) {
    auto* row = new QHBoxLayout(this);
    row->setContentsMargins(0, 0, 0, 0);
    row->setSpacing(2);
    struct Spec {
        const char* name;
        QString tip;
        double min, max, step;
    };
    const std::array<Spec, 5> specs{{
        {"uvScaleU", tr("Tiling in U (how often the texture repeats across the UV square)"),
         -kUvScaleLimit, kUvScaleLimit, 0.1},
        {"uvScaleV", tr("Tiling in V"), -kUvScaleLimit, kUvScaleLimit, 0.1},
        {"uvOffsetU", tr("Offset in U, after tiling and rotation (UV units)"), -kUvOffsetLimit,
         kUvOffsetLimit, 0.05},
        {"uvOffsetV",
         tr("Offset in V, after tiling and rotation (UV units; V runs down the "
            "image)"),
         -kUvOffsetLimit, kUvOffsetLimit, 0.05},
        {"uvRotation", tr("Rotation in degrees, counter-clockwise, after tiling"),
         -kUvRotationLimit, kUvRotationLimit, 5.0},
    }};
    auto* label = new QLabel(tr("UV"), this);
    label->setToolTip(tr("Tiling, offset and rotation of the texture coordinates (glTF's "
                         "KHR_texture_transform)"));
    row->addWidget(label);
    for (size_t i = 0; i < specs.size(); ++i) {
        auto* box = new QDoubleSpinBox(this);
        box->setObjectName(namePrefix + QLatin1Char('/') + QLatin1String(specs[i].name));
        box->setToolTip(specs[i].tip);
        box->setRange(specs[i].min, specs[i].max);
        box->setDecimals(i == 4 ? 1 : 3);
        box->setSingleStep(specs[i].step);
        box->setKeyboardTracking(false); // one command per committed value, not per keystroke
        box->setFocusPolicy(Qt::StrongFocus);
        if (i == 4)
            box->setSuffix(QStringLiteral("°"));
        box->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
        connect(box, &QDoubleSpinBox::valueChanged, this, [this] {
            if (!m_refreshing)
                commit();
        });
        row->addWidget(box, 1);
        m_boxes[i] = box;
    }
    m_reset = new QToolButton(this);
    m_reset->setObjectName(namePrefix + QStringLiteral("/uvReset"));
    m_reset->setText(tr("1:1"));
    m_reset->setToolTip(tr("No UV transform (tiling 1, offset 0, rotation 0)"));
    connect(m_reset, &QToolButton::clicked, this, [this] {
        TextureRef ref = m_controller->material().texture(m_slot);
        if (ref.empty())
            return;
        ref.uv = UvTransform{};
        m_controller->editTexture(
            m_slot, ref, tr("Reset %1 UV transform").arg(fromView(textureSlotMeta(m_slot).label)));
    });
    row->addWidget(m_reset);
    refresh();
}

void UvTransformEditor::refresh() {
    const TextureRef& ref = m_controller->material().texture(m_slot);
    m_refreshing = true;
    const float values[5] = {ref.uv.scale.x, ref.uv.scale.y, ref.uv.offset.x, ref.uv.offset.y,
                             ref.uv.rotation};
    for (size_t i = 0; i < m_boxes.size(); ++i) {
        const QSignalBlocker block(m_boxes[i]);
        m_boxes[i]->setValue(double(values[i]));
        m_boxes[i]->setEnabled(!ref.empty());
    }
    m_reset->setEnabled(!ref.empty() && !ref.uv.isIdentity());
    m_refreshing = false;
}

void UvTransformEditor::commit() {
    TextureRef ref = m_controller->material().texture(m_slot);
    if (ref.empty())
        return;
    UvTransform uv;
    uv.scale = {float(m_boxes[0]->value()), float(m_boxes[1]->value())};
    uv.offset = {float(m_boxes[2]->value()), float(m_boxes[3]->value())};
    uv.rotation = float(m_boxes[4]->value());
    // A tiling of 0 would collapse the texture to one texel (the file reader refuses it too).
    if (uv.scale.x == 0.0f || uv.scale.y == 0.0f) {
        refresh();
        return;
    }
    if (uv == ref.uv)
        return;
    ref.uv = uv;
    m_controller->editTexture(
        m_slot, ref, tr("Set %1 UV transform").arg(fromView(textureSlotMeta(m_slot).label)));
}

} // namespace velvet::ui
