#include "ui/atlas/atlas_panel.h"

#include "ui/atlas/atlas_view.h"
#include "ui/commands/atlas_commands.h"
#include "ui/document_controller.h"

#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QMenu>
#include <QTabBar>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>

namespace velvet::ui {

AtlasPanel::AtlasPanel(DocumentController* controller, QWidget* parent)
    : QWidget(parent), m_controller(controller), m_model(new AtlasModel(controller, this)),
      m_tabs(new QTabBar(this)), m_view(new AtlasView(this)), m_channel(new QComboBox(this)),
      m_slot(new QComboBox(this)), m_status(new QLabel(this)) {
    setObjectName(QStringLiteral("atlasPanel"));
    m_tabs->setObjectName(QStringLiteral("atlasTabs"));
    for (int k = 0; k < kAtlasKindCount; ++k)
        m_tabs->addTab(AtlasModel::kindLabel(AtlasKind(k)));
    m_tabs->setTabToolTip(int(AtlasKind::Material),
                          tr("R specular, G roughness, B metallic (the seeds' packing)"));

    auto button = [this](const QString& text, const QString& name, const QString& tip) {
        auto* b = new QToolButton(this);
        b->setText(text);
        b->setObjectName(name);
        b->setToolTip(tip);
        return b;
    };
    QToolButton* add = button(tr("Add…"), QStringLiteral("atlasAddButton"),
                              tr("Add images to this atlas (packed with padding)"));
    QToolButton* repackButton = button(tr("Repack"), QStringLiteral("atlasRepackButton"),
                                       tr("Pack every region again from scratch"));
    QToolButton* exportButton = button(tr("Export…"), QStringLiteral("atlasExportButton"),
                                       tr("Write the atlas image (PNG, EXR, …)"));
    QToolButton* exportAllButton = button(tr("Export all…"), QStringLiteral("atlasExportAllButton"),
                                          tr("Write every non-empty atlas image into a folder"));
    // The material atlas repacked for an engine (core/channel_packing.h).
    QToolButton* exportPacked =
        button(tr("Export packed…"), QStringLiteral("atlasExportPackedButton"),
               tr("Write the material atlas (R specular, G roughness, B metallic) in an engine's "
                  "channel layout: glTF metallic-roughness, Unreal ORM or Unity HDRP mask map"));
    exportPacked->setPopupMode(QToolButton::InstantPopup);
    auto* packedMenu = new QMenu(exportPacked);
    packedMenu->setObjectName(QStringLiteral("atlasExportPackedMenu"));
    for (PackLayout layout :
         {PackLayout::GltfMetallicRoughness, PackLayout::UnrealOrm, PackLayout::HdrpMaskMap}) {
        const std::string_view label = packLayoutLabel(layout);
        packedMenu->addAction(QString::fromUtf8(label.data(), qsizetype(label.size())), this,
                              [this, layout] { exportPackedDialog(layout); });
    }
    exportPacked->setMenu(packedMenu);
    QToolButton* assign = button(tr("Assign"), QStringLiteral("atlasAssignButton"),
                                 tr("Use the selected region in the chosen material slot"));
    m_channel->setObjectName(QStringLiteral("atlasChannelCombo"));
    m_channel->addItem(tr("RGB"), -1);
    m_channel->addItem(tr("R"), 0);
    m_channel->addItem(tr("G"), 1);
    m_channel->addItem(tr("B"), 2);
    m_channel->addItem(tr("A"), 3);
    m_channel->setToolTip(tr("Isolate one channel (view only)"));
    m_slot->setObjectName(QStringLiteral("atlasSlotCombo"));
    for (int i = 0; i < kTextureSlotCount; ++i)
        m_slot->addItem(QString::fromUtf8(textureSlotMeta(TextureSlot(i)).label.data(),
                                          qsizetype(textureSlotMeta(TextureSlot(i)).label.size())),
                        i);
    m_status->setObjectName(QStringLiteral("atlasStatus"));
    m_status->setWordWrap(true);

    auto* row = new QHBoxLayout;
    row->addWidget(add);
    row->addWidget(repackButton);
    row->addWidget(exportButton);
    row->addWidget(exportAllButton);
    row->addWidget(exportPacked);
    row->addWidget(m_channel);
    row->addStretch();
    auto* assignRow = new QHBoxLayout;
    assignRow->addWidget(new QLabel(tr("Region →"), this));
    assignRow->addWidget(m_slot, 1);
    assignRow->addWidget(assign);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    layout->addWidget(m_tabs);
    layout->addLayout(row);
    layout->addWidget(m_view, 1);
    layout->addLayout(assignRow);
    layout->addWidget(m_status);

    connect(add, &QToolButton::clicked, this, &AtlasPanel::addImages);
    connect(repackButton, &QToolButton::clicked, this, &AtlasPanel::repack);
    connect(exportButton, &QToolButton::clicked, this, &AtlasPanel::exportCurrent);
    connect(exportAllButton, &QToolButton::clicked, this, &AtlasPanel::exportAllDialog);
    connect(assign, &QToolButton::clicked, this, &AtlasPanel::assignSelectedToChosenSlot);
    connect(m_channel, &QComboBox::currentIndexChanged, this,
            [this] { m_view->setChannel(m_channel->currentData().toInt()); });
    connect(m_tabs, &QTabBar::currentChanged, this, [this] {
        m_view->setSelectedRegion(-1);
        m_slot->setCurrentIndex(int(AtlasModel::defaultSlot(currentKind())));
        refresh();
    });
    connect(m_model, &AtlasModel::atlasChanged, this, [this](AtlasKind kind) {
        if (kind == currentKind())
            refresh();
    });
    connect(m_view, &AtlasView::regionEdited, this,
            [this](int index, AtlasRegion region, int mergeKey) {
                m_model->editRegion(currentKind(), index, region, mergeKey);
            });
    m_slot->setCurrentIndex(int(AtlasModel::defaultSlot(currentKind())));
    refresh();
}

AtlasKind AtlasPanel::currentKind() const {
    return AtlasKind(std::max(0, m_tabs->currentIndex()));
}

void AtlasPanel::setCurrentKind(AtlasKind kind) {
    m_tabs->setCurrentIndex(int(kind));
}

void AtlasPanel::refresh() {
    const AtlasDocument& a = m_model->atlas(currentKind());
    std::vector<AtlasRegion> regions;
    for (const AtlasEntry& e : a.entries)
        regions.push_back(e.region);
    m_view->setAtlas(a.image, regions);
    if (a.entries.empty())
        m_status->setText(tr("Empty: add images. Atlases are saved with the scene; export "
                             "writes their images."));
    else
        m_status->setText(tr("%1 x %2, %n region(s), padding %3", nullptr, int(a.entries.size()))
                              .arg(a.width)
                              .arg(a.height)
                              .arg(a.padding));
}

void AtlasPanel::report(const QString& message) {
    m_status->setText(message);
}

void AtlasPanel::addImages() {
    const QStringList files = QFileDialog::getOpenFileNames(
        this, tr("Add images to the %1 atlas").arg(AtlasModel::kindLabel(currentKind())), QString(),
        tr("Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.hdr *.tga *.bmp)"));
    if (files.isEmpty())
        return;
    QString error;
    if (!m_model->addImageFiles(currentKind(), files, &error))
        report(error);
}

void AtlasPanel::repack() {
    QString error;
    if (!m_model->repack(currentKind(), &error))
        report(error);
}

void AtlasPanel::exportCurrent() {
    const QString path = QFileDialog::getSaveFileName(
        this, tr("Export the %1 atlas").arg(AtlasModel::kindLabel(currentKind())), QString(),
        tr("PNG (*.png);;OpenEXR (*.exr);;TIFF (*.tif)"));
    if (path.isEmpty())
        return;
    QString error;
    if (m_model->exportAtlas(currentKind(), path, &error))
        report(tr("Exported %1").arg(path));
    else
        report(error);
}

void AtlasPanel::exportPackedDialog(PackLayout layout) {
    const std::string_view label = packLayoutLabel(layout);
    const QString path = QFileDialog::getSaveFileName(
        this,
        tr("Export the material atlas as %1")
            .arg(QString::fromUtf8(label.data(), qsizetype(label.size()))),
        QString(), tr("PNG, 16 bit (*.png);;OpenEXR (*.exr)"));
    if (path.isEmpty())
        return;
    QString error;
    if (m_model->exportMaterialAtlasPacked(layout, path, &error))
        report(tr("Exported %1").arg(path));
    else
        report(error);
}

void AtlasPanel::exportAllDialog() {
    const QString folder =
        QFileDialog::getExistingDirectory(this, tr("Export the atlas images into"));
    if (folder.isEmpty())
        return;
    const QString file = m_controller->filePath();
    const QString stem =
        file.isEmpty() ? QStringLiteral("atlas") : QFileInfo(file).completeBaseName();
    QStringList written;
    QString error;
    if (m_model->exportAll(folder, stem, QStringLiteral("png"), &written, &error))
        report(tr("Exported %1").arg(written.join(QStringLiteral(", "))));
    else
        report(error);
}

void AtlasPanel::assignSelectedToChosenSlot() {
    QString error;
    if (!assignSelected(TextureSlot(m_slot->currentData().toInt()), &error))
        report(error);
}

bool AtlasPanel::assignSelected(TextureSlot slot, QString* error) {
    const AtlasKind kind = currentKind();
    const int index = m_view->selectedRegion();
    const AtlasDocument& a = m_model->atlas(kind);
    if (index < 0 || index >= int(a.entries.size())) {
        if (error)
            *error = tr("Select a region first");
        return false;
    }
    const QString file = m_model->ensureFile(kind, error);
    if (file.isEmpty())
        return false;
    TextureRef ref = m_controller->material().texture(slot);
    ref.file = file.toStdString();
    ref.useRegion = true;
    ref.region = m_model->atlas(kind).entries[size_t(index)].region;
    m_controller->editTexture(
        slot, ref,
        tr("Assign %1 region to %2")
            .arg(AtlasModel::kindLabel(kind),
                 QString::fromUtf8(textureSlotMeta(slot).label.data(),
                                   qsizetype(textureSlotMeta(slot).label.size()))));
    return true;
}

} // namespace velvet::ui
