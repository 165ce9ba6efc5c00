#include "ui/texture_set_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>

namespace velvet::ui {
namespace {

constexpr const char* kSizeKey = "export/textureSet/size";
constexpr const char* kTypeKey = "export/textureSet/image";
constexpr const char* kBitsKey = "export/textureSet/bits";
constexpr const char* kNormalKey = "export/textureSet/normal"; ///< "", "opengl", "directx"

/// The bits a file type holds, its default first (checkTextureSetOptions).
std::vector<int> bitsChoices(TextureFileType type) {
    switch (type) {
    case TextureFileType::Png:
        return {8, 16};
    case TextureFileType::Exr:
        return {16, 32};
    default:
        return {8};
    }
}

QString bitsLabel(TextureFileType type, int bits) {
    if (type == TextureFileType::Exr)
        return bits == 16 ? TextureSetDialog::tr("16 (half float)")
                          : TextureSetDialog::tr("32 (float)");
    return QString::number(bits);
}

} // namespace

TextureSetDialog::TextureSetDialog(TextureSetTarget target, QWidget* parent)
    : QDialog(parent), m_target(target) {
    setWindowTitle(tr("Texture set for %1")
                       .arg(QString::fromUtf8(textureSetTargetLabel(target).data(),
                                              qsizetype(textureSetTargetLabel(target).size()))));
    auto* form = new QFormLayout(this);
    m_size = new QSpinBox(this);
    m_size->setRange(1, 8192);
    m_size->setSuffix(tr(" px"));
    m_size->setToolTip(tr("Width and height of every map (velvet export --size)."));
    form->addRow(tr("Size"), m_size);
    m_type = new QComboBox(this);
    for (int t = 0; t < int(TextureFileType::Count); ++t) {
        const std::string_view id = textureFileTypeId(TextureFileType(t));
        m_type->addItem(QString::fromUtf8(id.data(), qsizetype(id.size())).toUpper(), t);
    }
    m_type->setToolTip(tr("The maps' file type (--image): EXR keeps scene-linear colour."));
    form->addRow(tr("File type"), m_type);
    m_bits = new QComboBox(this);
    m_bits->setToolTip(tr("Bits per channel (--bits): the choices the file type holds."));
    form->addRow(tr("Bits per channel"), m_bits);
    m_normal = new QComboBox(this);
    const bool directx = defaultNormalConvention(target) == NormalConvention::DirectX;
    m_normal->addItem(
        tr("The engine's (%1)").arg(directx ? tr("DirectX, green down") : tr("OpenGL, green up")),
        QString());
    m_normal->addItem(tr("OpenGL, green up"), QStringLiteral("opengl"));
    m_normal->addItem(tr("DirectX, green down"), QStringLiteral("directx"));
    m_normal->setToolTip(tr("The normal map's green channel (--normal)."));
    form->addRow(tr("Normal map"), m_normal);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
    buttons->button(QDialogButtonBox::Ok)->setText(tr("Export"));
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    form->addRow(buttons);
    connect(m_type, &QComboBox::currentIndexChanged, this, [this] { fillBits(0); });

    // The remembered settings, else the CLI's defaults.
    const QSettings settings;
    TextureSetOptions o;
    o.target = target;
    o.size = settings.value(kSizeKey, o.size).toInt();
    o.fileType = textureFileTypeFromId(
                     settings.value(kTypeKey, QStringLiteral("png")).toString().toStdString())
                     .value_or(TextureFileType::Png);
    o.bits = settings.value(kBitsKey, 0).toInt();
    const QString normal = settings.value(kNormalKey).toString();
    if (!normal.isEmpty())
        o.normal = normal == QLatin1String("directx") ? NormalConvention::DirectX
                                                      : NormalConvention::OpenGl;
    if (!checkTextureSetOptions(o).empty())
        o = TextureSetOptions{target};
    setOptions(o);
}

void TextureSetDialog::fillBits(int preferred) {
    const auto type = TextureFileType(m_type->currentData().toInt());
    const QSignalBlocker block(m_bits);
    m_bits->clear();
    for (int bits : bitsChoices(type))
        m_bits->addItem(bitsLabel(type, bits), bits);
    const int index = m_bits->findData(preferred);
    m_bits->setCurrentIndex(index < 0 ? 0 : index);
}

void TextureSetDialog::setOptions(const TextureSetOptions& o) {
    m_size->setValue(o.size);
    {
        const QSignalBlocker block(m_type);
        m_type->setCurrentIndex(m_type->findData(int(o.fileType)));
    }
    fillBits(o.bits);
    m_normal->setCurrentIndex(!o.normal ? 0 : *o.normal == NormalConvention::OpenGl ? 1 : 2);
}

TextureSetOptions TextureSetDialog::options() const {
    TextureSetOptions o;
    o.target = m_target;
    o.size = m_size->value();
    o.fileType = TextureFileType(m_type->currentData().toInt());
    o.bits = m_bits->currentData().toInt();
    const QString normal = m_normal->currentData().toString();
    if (!normal.isEmpty())
        o.normal = normal == QLatin1String("directx") ? NormalConvention::DirectX
                                                      : NormalConvention::OpenGl;
    return o;
}

void TextureSetDialog::remember() const {
    const TextureSetOptions o = options();
    QSettings settings;
    settings.setValue(kSizeKey, o.size);
    const std::string_view type = textureFileTypeId(o.fileType);
    settings.setValue(kTypeKey, QString::fromUtf8(type.data(), qsizetype(type.size())));
    settings.setValue(kBitsKey, o.bits);
    settings.setValue(kNormalKey, m_normal->currentData().toString());
}

} // namespace velvet::ui
