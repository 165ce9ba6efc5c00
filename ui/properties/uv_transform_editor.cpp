#include "ui/properties/uv_transform_editor.h"

#include "ui/document_controller.h"

#include <QDoubleSpinBox>
#include <QGridLayout>
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
    // Three short rows under the slot's thumbnail, so the panel needs no extra width:
    //   Tiling   [u] [v]
    //   Offset   [u] [v]
    //   Rotation [deg] [1:1]
    auto* grid = new QGridLayout(this);
    grid->setContentsMargins(0, 0, 0, 0);
    grid->setHorizontalSpacing(4);
    grid->setVerticalSpacing(2);
    struct Spec {
        const char* name;
        QString tip;
        double min, max, step;
        int row, column;
    };
    const std::array<Spec, 5> specs{{
        {"uvScaleU", tr("Tiling in U (how often the texture repeats across the UV square)"),
         -kUvScaleLimit, kUvScaleLimit, 0.1, 0, 1},
        {"uvScaleV", tr("Tiling in V"), -kUvScaleLimit, kUvScaleLimit, 0.1, 0, 2},
        {"uvOffsetU", tr("Offset in U, after tiling and rotation (UV units)"), -kUvOffsetLimit,
         kUvOffsetLimit, 0.05, 1, 1},
        {"uvOffsetV",
         tr("Offset in V, after tiling and rotation (UV units; V runs down the image)"),
         -kUvOffsetLimit, kUvOffsetLimit, 0.05, 1, 2},
        {"uvRotation", tr("Rotation in degrees, counter-clockwise, after tiling"),
         -kUvRotationLimit, kUvRotationLimit, 5.0, 2, 1},
    }};
    const QString transformTip =
        tr("Tiling, offset and rotation of the texture coordinates (glTF's KHR_texture_transform)");
    const auto addLabel = [&](const QString& text, int row, int column) {
        auto* label = new QLabel(text, this);
        label->setToolTip(transformTip);
        grid->addWidget(label, row, column);
    };
    addLabel(tr("Tiling"), 0, 0);
    addLabel(tr("Offset"), 1, 0);
    addLabel(tr("Rotation"), 2, 0);
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
        // The range's widest text ("-1000.000") must not set the panel's width: the boxes share
        // what the dock gives them (Properties must not scroll sideways).
        box->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
        box->setMinimumWidth(48);
        connect(box, &QDoubleSpinBox::valueChanged, this, [this] {
            if (!m_refreshing)
                commit();
        });
        grid->addWidget(box, specs[i].row, specs[i].column);
        m_boxes[i] = box;
    }
    grid->setColumnStretch(1, 1);
    grid->setColumnStretch(2, 1);
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
    grid->addWidget(m_reset, 2, 2, Qt::AlignLeft);
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
