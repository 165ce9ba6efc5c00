#include "ui/properties/linear_color_picker.h"

#include "ui/properties/param_editor.h"
#include "ui/viewport_widget.h"

#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMouseEvent>
#include <QPainter>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>
#include <QWindow>
#include <algorithm>
#include <cmath>
#include <glm/common.hpp>

namespace velvet::ui {

/// The hue / saturation disc at the picker's value: hue round the circle, saturation from the
/// centre out, as Blender's wheel. A press starts a gesture; every move is sent with its key.
class HueWheel final : public QWidget {
public:
    explicit HueWheel(LinearColorPicker* picker) : QWidget(picker), m_picker(picker) {
        setObjectName(QStringLiteral("colorWheel"));
        setFixedSize(170, 170);
        setCursor(Qt::CrossCursor);
    }

protected:
    void paintEvent(QPaintEvent*) override {
        QPainter p(this);
        p.setRenderHint(QPainter::Antialiasing);
        const QRectF disc = discRect();
        QConicalGradient hues(disc.center(), 0.0);
        for (int i = 0; i <= 12; ++i)
            hues.setColorAt(i / 12.0, QColor::fromHsvF(float(i % 12) / 12.0f, 1.0f, 1.0f));
        p.setPen(Qt::NoPen);
        p.setBrush(hues);
        p.drawEllipse(disc);
        QRadialGradient white(disc.center(), disc.width() / 2);
        white.setColorAt(0.0, Qt::white);
        white.setColorAt(1.0, QColor(255, 255, 255, 0));
        p.setBrush(white);
        p.drawEllipse(disc);
        p.setBrush(QColor(0, 0, 0, int(std::lround((1.0f - m_picker->m_val) * 255.0f))));
        p.drawEllipse(disc);
        // The marker at the current hue and saturation.
        const float angle = m_picker->m_hue * 2.0f * float(M_PI);
        const QPointF at = disc.center() + QPointF(std::cos(angle), -std::sin(angle)) *
                                               (m_picker->m_sat * disc.width() / 2);
        p.setBrush(Qt::NoBrush);
        p.setPen(QPen(Qt::black, 2));
        p.drawEllipse(at, 5, 5);
        p.setPen(QPen(Qt::white, 1));
        p.drawEllipse(at, 5, 5);
    }
    void mousePressEvent(QMouseEvent* e) override {
        m_key = LinearColorPicker::nextGestureKey();
        pick(e->position());
    }
    void mouseMoveEvent(QMouseEvent* e) override {
        if (e->buttons() & Qt::LeftButton)
            pick(e->position());
    }
    void mouseReleaseEvent(QMouseEvent*) override { m_key = 0; }

private:
    QRectF discRect() const { return QRectF(rect()).adjusted(6, 6, -6, -6); }
    void pick(QPointF pos) {
        const QRectF disc = discRect();
        const QPointF d = pos - disc.center();
        const float radius = float(disc.width() / 2);
        float hue = std::atan2(float(-d.y()), float(d.x())) / (2.0f * float(M_PI));
        if (hue < 0.0f)
            hue += 1.0f;
        const float sat = std::min(1.0f, float(std::hypot(d.x(), d.y())) / radius);
        m_picker->setFromHsv(hue, sat, m_picker->m_val, m_key);
        update();
    }

    LinearColorPicker* m_picker;
    int m_key = 0;
};

namespace {

QDoubleSpinBox* channelBox(const QString& name, double max, QWidget* parent) {
    auto* box = new QDoubleSpinBox(parent);
    box->setObjectName(name);
    box->setRange(0.0, max);
    box->setDecimals(4);
    box->setSingleStep(0.01);
    box->setKeyboardTracking(false); // a typed value is one step, on Enter
    return box;
}

} // namespace

int LinearColorPicker::nextGestureKey() {
    return ParamEditor::nextGestureKey();
}

LinearColorPicker::LinearColorPicker(const QString& title, glm::vec3 linear,
                                     const PickerColorSpace& space, QWidget* parent)
    : QDialog(parent), m_space(space) {
    setObjectName(QStringLiteral("linearColorPicker"));
    setWindowTitle(title);
    setAttribute(Qt::WA_DeleteOnClose);

    m_wheel = new HueWheel(this);
    m_value = new QSlider(Qt::Vertical, this);
    m_value->setObjectName(QStringLiteral("colorValue"));
    m_value->setRange(0, 1000);
    m_value->setToolTip(tr("Value (display brightness)"));
    connect(m_value, &QSlider::sliderPressed, this, [this] { m_sliderKey = nextGestureKey(); });
    connect(m_value, &QSlider::sliderReleased, this, [this] { m_sliderKey = 0; });
    connect(m_value, &QSlider::valueChanged, this, [this](int v) {
        if (!m_showing)
            setFromHsv(m_hue, m_sat, float(v) / 1000.0f, m_value->isSliderDown() ? m_sliderKey : 0);
    });

    m_swatch = new QWidget(this);
    m_swatch->setObjectName(QStringLiteral("colorSwatch"));
    m_swatch->setFixedHeight(28);
    m_swatch->setAutoFillBackground(true);

    auto* form = new QFormLayout;
    auto* displayRow = new QHBoxLayout;
    auto* linearRow = new QHBoxLayout;
    static const char* const kChannels[3] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c) {
        m_displayBoxes[c] = channelBox(QStringLiteral("display:") + kChannels[c], 1.0, this);
        m_linearBoxes[c] = channelBox(QStringLiteral("linear:") + kChannels[c], 100.0, this);
        displayRow->addWidget(m_displayBoxes[c]);
        linearRow->addWidget(m_linearBoxes[c]);
        connect(m_displayBoxes[c], &QDoubleSpinBox::valueChanged, this, [this, c](double v) {
            if (m_showing)
                return;
            glm::vec3 d = m_display;
            d[c] = float(v);
            setFromDisplay(d, 0);
        });
        connect(m_linearBoxes[c], &QDoubleSpinBox::valueChanged, this, [this, c](double v) {
            if (m_showing)
                return;
            glm::vec3 l = m_linear;
            l[c] = float(v);
            setFromLinearValue(l, 0);
        });
    }
    m_hex = new QLineEdit(this);
    m_hex->setObjectName(QStringLiteral("colorHex"));
    m_hex->setToolTip(tr("The display-encoded colour as #RRGGBB (what the screen shows)"));
    m_hex->setMaxLength(7);
    connect(m_hex, &QLineEdit::editingFinished, this, [this] {
        const QColor c(m_hex->text().trimmed());
        if (c.isValid() && c.name() != hex())
            setFromDisplay(glm::vec3(c.redF(), c.greenF(), c.blueF()), 0);
        else
            showValues();
    });
    const QString linearName =
        m_space.colorManagement && m_space.colorManagement->isLoaded()
            ? QString::fromStdString(m_space.colorManagement->roleColorSpace("scene_linear"))
            : QString();
    const QString stored = linearName.isEmpty() ? tr("Linear Rec.709") : linearName;
    form->addRow(tr("Display (%1)").arg(m_space.name()), displayRow);
    form->addRow(tr("Hex (display)"), m_hex);
    form->addRow(tr("Scene-linear (%1)").arg(stored), linearRow);
    m_intensity = new QDoubleSpinBox(this);
    m_intensity->setObjectName(QStringLiteral("colorIntensity"));
    m_intensity->setKeyboardTracking(false);
    m_intensity->setDecimals(2);
    m_intensityLabel = new QLabel(tr("Intensity"), this);
    form->addRow(m_intensityLabel, m_intensity);
    m_intensity->hide();
    m_intensityLabel->hide();
    connect(m_intensity, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (!m_showing)
            emit intensityEdited(float(v), 0);
    });

    m_eyedropper = new QPushButton(tr("Pick from the viewport"), this);
    m_eyedropper->setObjectName(QStringLiteral("colorEyedropper"));
    m_eyedropper->setCheckable(true);
    m_eyedropper->setToolTip(tr("Then click a pixel of the viewport: the colour becomes the "
                                "scene-linear value that displays as that pixel"));
    m_eyedropper->hide();
    connect(m_eyedropper, &QPushButton::toggled, this, [this](bool on) {
        if (!m_viewport)
            return;
        if (on)
            m_viewport->glWindow()->installEventFilter(this);
        else
            m_viewport->glWindow()->removeEventFilter(this);
    });

    m_spaceLabel = new QLabel(this);
    m_spaceLabel->setObjectName(QStringLiteral("colorSpaces"));
    m_spaceLabel->setWordWrap(true);
    m_spaceLabel->setText(tr("Wheel, value and hex are in the viewport's display space (%1); "
                             "the document stores scene-linear values (%2, OpenColorIO's "
                             "scene_linear).")
                              .arg(m_space.name(), stored));

    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, this);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::close);

    auto* top = new QHBoxLayout;
    top->addWidget(m_wheel);
    top->addWidget(m_value);
    auto* right = new QVBoxLayout;
    right->addWidget(m_swatch);
    right->addLayout(form);
    right->addWidget(m_eyedropper);
    right->addStretch(1);
    top->addLayout(right, 1);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(top);
    layout->addWidget(m_spaceLabel);
    layout->addWidget(buttons);
    setLinear(linear);
}

void LinearColorPicker::setIntensity(float value, float max, const QString& unit) {
    const QSignalBlocker block(m_intensity);
    m_intensity->setRange(0.0, max);
    m_intensity->setSuffix(unit.isEmpty() ? QString() : QLatin1Char(' ') + unit);
    m_intensity->setValue(value);
    m_intensity->show();
    m_intensityLabel->show();
}

void LinearColorPicker::setIntensityValue(float value) {
    const QSignalBlocker block(m_intensity);
    m_intensity->setValue(value);
}

void LinearColorPicker::setViewport(ViewportWidget* viewport) {
    m_viewport = viewport;
    m_eyedropper->setVisible(viewport != nullptr);
}

QString LinearColorPicker::hex() const {
    return QColor::fromRgbF(m_display.r, m_display.g, m_display.b).name();
}

void LinearColorPicker::setLinear(glm::vec3 linear) {
    m_linear = linear;
    m_display = glm::clamp(m_space.toDisplay(linear), glm::vec3(0.0f), glm::vec3(1.0f));
    const QColor c = QColor::fromRgbF(m_display.r, m_display.g, m_display.b);
    float h = 0, s = 0, v = 0;
    c.getHsvF(&h, &s, &v);
    if (h >= 0.0f && s > 0.0f) // grey has no hue: keep the last one
        m_hue = h;
    m_sat = s;
    m_val = v;
    showValues();
}

void LinearColorPicker::setFromHsv(float h, float s, float v, int key) {
    const QColor c = QColor::fromHsvF(std::clamp(h, 0.0f, 1.0f), std::clamp(s, 0.0f, 1.0f),
                                      std::clamp(v, 0.0f, 1.0f));
    m_display = glm::vec3(c.redF(), c.greenF(), c.blueF());
    m_linear = m_space.toLinear(m_display);
    m_hue = h;
    m_sat = s;
    m_val = v;
    showValues();
    emit colorEdited(m_linear, key);
}

void LinearColorPicker::setFromDisplay(glm::vec3 display, int key) {
    setLinear(m_space.toLinear(glm::clamp(display, glm::vec3(0.0f), glm::vec3(1.0f))));
    emit colorEdited(m_linear, key);
}

void LinearColorPicker::setFromLinearValue(glm::vec3 linear, int key) {
    setLinear(glm::max(linear, glm::vec3(0.0f)));
    emit colorEdited(m_linear, key);
}

void LinearColorPicker::showValues() {
    const bool was = m_showing;
    m_showing = true;
    for (int c = 0; c < 3; ++c) {
        const QSignalBlocker a(m_displayBoxes[c]), b(m_linearBoxes[c]);
        m_displayBoxes[c]->setValue(m_display[c]);
        m_linearBoxes[c]->setValue(m_linear[c]);
    }
    m_hex->setText(hex());
    {
        const QSignalBlocker block(m_value);
        if (!m_value->isSliderDown())
            m_value->setValue(int(std::lround(m_val * 1000.0f)));
    }
    QPalette palette = m_swatch->palette();
    palette.setColor(QPalette::Window, QColor::fromRgbF(m_display.r, m_display.g, m_display.b));
    m_swatch->setPalette(palette);
    m_wheel->update();
    m_showing = was;
}

bool LinearColorPicker::eventFilter(QObject* watched, QEvent* event) {
    // The eyedropper: the next left click on the viewport picks, and does not orbit.
    if (m_viewport && watched == m_viewport->glWindow() &&
        event->type() == QEvent::MouseButtonPress) {
        auto* mouse = static_cast<QMouseEvent*>(event);
        if (mouse->button() == Qt::LeftButton) {
            pickAt(mouse->position().toPoint());
            m_eyedropper->setChecked(false);
            return true;
        }
    }
    return QDialog::eventFilter(watched, event);
}

void LinearColorPicker::pickAt(QPoint pos) {
    // The pixel as displayed (the renderer's display-encoded frame), back through the inverse of
    // the picker's display transform: the linear value that shows as that pixel, as Blender's
    // eyedropper does; the refined mean once the still view has settled, as it is on screen.
    const QImage frame = m_viewport->grabFramebuffer(nullptr, /*settled=*/true);
    if (frame.isNull())
        return;
    const qreal dpr = frame.devicePixelRatio();
    const QPoint px(std::clamp(int(pos.x() * dpr), 0, frame.width() - 1),
                    std::clamp(int(pos.y() * dpr), 0, frame.height() - 1));
    const QColor c = frame.pixelColor(px);
    setFromDisplay(glm::vec3(c.redF(), c.greenF(), c.blueF()), 0);
}

} // namespace velvet::ui
