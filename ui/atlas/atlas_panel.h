#pragma once
/// @file atlas_panel.h
/// The Atlas dock: tabs for the albedo, material (R specular, G roughness, B metallic) and normal
/// atlases; the atlas image with its regions (AtlasView); add images (packed with padding by
/// core/atlas_packing), repack, move and resize regions by dragging (undoable, one command per
/// drag), assign the selected region to a material texture slot (undoable), isolate R/G/B/A
/// (view state) and export the atlas images. The atlases belong to the document (saved beside the
/// scene, see AtlasModel).

#include "ui/models/atlas_model.h"

#include <QWidget>

class QComboBox;
class QLabel;
class QTabBar;

namespace velvet::ui {

class AtlasView;
class DocumentController;

class AtlasPanel : public QWidget {
    Q_OBJECT
public:
    explicit AtlasPanel(DocumentController* controller, QWidget* parent = nullptr);

    AtlasModel* model() const { return m_model; }
    AtlasView* view() const { return m_view; }
    AtlasKind currentKind() const;
    void setCurrentKind(AtlasKind kind);

    /// Assigns the selected region of the current atlas to @p slot of the material: the slot's
    /// TextureRef gets the atlas file (exported first when it has none), useRegion and the
    /// region. One undo command. False + @p error when nothing is selected or export failed.
    bool assignSelected(TextureSlot slot, QString* error);

public slots:
    /// Asks for image files and adds them to the current atlas.
    void addImages();
    void repack();
    /// Asks for a file name and exports the current atlas.
    void exportCurrent();
    /// Asks for a file and writes the material atlas in @p layout.
    void exportPackedDialog(PackLayout layout);
    /// Asks for a folder and exports every non-empty atlas image into it (PNG).
    void exportAllDialog();
    void assignSelectedToChosenSlot();

private:
    void refresh();
    void report(const QString& message);

    DocumentController* m_controller;
    AtlasModel* m_model;
    QTabBar* m_tabs;
    AtlasView* m_view;
    QComboBox* m_channel;
    QComboBox* m_slot;
    QLabel* m_status;
};

} // namespace velvet::ui
