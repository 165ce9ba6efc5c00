#pragma once
/// @file texture_set_dialog.h
/// File > Export…'s texture-set settings, asked once the save dialog chose an engine's texture
/// set: the maps' size, file type (PNG / TGA / EXR), bits per channel (the choices the type
/// holds) and the normal map's green channel — the CLI's --size, --image, --bits and --normal,
/// with the CLI's defaults (1024, PNG, the type's default bits, the engine's convention). The
/// last settings are remembered (QSettings) and offered again.

#include "core/texture_set_export.h"

#include <QDialog>

class QComboBox;
class QSpinBox;
class QLabel;

namespace velvet::ui {

class TextureSetDialog : public QDialog {
    Q_OBJECT
public:
    /// Settings for @p target's set, starting from the remembered ones (else the CLI's defaults).
    explicit TextureSetDialog(TextureSetTarget target, QWidget* parent = nullptr);

    /// The settings as chosen (target included), always valid (checkTextureSetOptions).
    TextureSetOptions options() const;
    /// Shows @p options in the controls (tests and the remembered settings).
    void setOptions(const TextureSetOptions& options);
    /// Remembers the current settings for the next export.
    void remember() const;

    QSpinBox* sizeBox() const { return m_size; }
    QComboBox* typeBox() const { return m_type; }
    QComboBox* bitsBox() const { return m_bits; }
    QComboBox* normalBox() const { return m_normal; }

private:
    void fillBits(int preferred);

    TextureSetTarget m_target;
    QSpinBox* m_size = nullptr;
    QComboBox* m_type = nullptr;
    QComboBox* m_bits = nullptr;
    QComboBox* m_normal = nullptr;
};

} // namespace velvet::ui
