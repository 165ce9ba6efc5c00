#include "ui/recovery_dialog.h"

#include <QDialogButtonBox>
#include <QDir>
#include <QFileInfo>
#include <QHeaderView>
#include <QLabel>
#include <QLocale>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>

namespace velvet::ui {
namespace {
constexpr int kRoleIndex = Qt::UserRole; ///< index into m_autosaves
} // namespace

RecoveryDialog::RecoveryDialog(const QList<Autosave::Recoverable>& autosaves, QWidget* parent)
    : QDialog(parent), m_autosaves(autosaves), m_list(new QTreeWidget(this)) {
    setObjectName(QStringLiteral("recoveryDialog"));
    setWindowTitle(tr("Recover unsaved changes"));
    auto* text = new QLabel(tr("Velvet was not closed cleanly and kept unsaved changes of these "
                               "documents. Recover one to continue where you left off; the others "
                               "stay and are offered again at the next start or when you open "
                               "their file."),
                            this);
    text->setWordWrap(true);

    m_list->setObjectName(QStringLiteral("recoveryList"));
    m_list->setHeaderLabels({tr("Document"), tr("Folder"), tr("Autosaved")});
    m_list->setRootIsDecorated(false);
    m_list->setSelectionMode(QAbstractItemView::SingleSelection);
    for (qsizetype i = 0; i < autosaves.size(); ++i) {
        const Autosave::Recoverable& a = autosaves[i];
        const QFileInfo document(a.documentPath);
        auto* item = new QTreeWidgetItem(m_list);
        item->setText(0, a.documentPath.isEmpty() ? tr("Untitled document") : document.fileName());
        item->setText(1, a.documentPath.isEmpty() ? QString()
                                                  : QDir::toNativeSeparators(document.path()));
        item->setText(2, QLocale().toString(a.written, QLocale::ShortFormat));
        item->setToolTip(0, a.documentPath.isEmpty() ? a.autosaveFile : a.documentPath);
        item->setData(0, kRoleIndex, int(i));
    }
    m_list->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
    if (m_list->topLevelItemCount() > 0)
        m_list->setCurrentItem(m_list->topLevelItem(0)); // the newest

    auto* buttons = new QDialogButtonBox(this);
    m_recover = buttons->addButton(tr("Recover"), QDialogButtonBox::AcceptRole);
    m_recover->setObjectName(QStringLiteral("recoverButton"));
    m_recover->setDefault(true);
    m_discard = buttons->addButton(tr("Discard"), QDialogButtonBox::DestructiveRole);
    m_discard->setObjectName(QStringLiteral("discardButton"));
    QPushButton* later = buttons->addButton(tr("Later"), QDialogButtonBox::RejectRole);
    later->setObjectName(QStringLiteral("laterButton"));
    // Each button does its own job; the box's accepted/rejected would close on Discard too.
    connect(m_recover, &QPushButton::clicked, this, [this] {
        if (QTreeWidgetItem* item = m_list->currentItem()) {
            m_chosen = m_autosaves[item->data(0, kRoleIndex).toInt()];
            accept();
        }
    });
    connect(m_discard, &QPushButton::clicked, this, [this] {
        QTreeWidgetItem* item = m_list->currentItem();
        if (!item)
            return;
        m_discarded << m_autosaves[item->data(0, kRoleIndex).toInt()].autosaveFile;
        delete item;
        if (m_list->topLevelItemCount() == 0)
            accept(); // nothing left to decide
        updateButtons();
    });
    connect(later, &QPushButton::clicked, this, &QDialog::reject);
    connect(m_list, &QTreeWidget::currentItemChanged, this, &RecoveryDialog::updateButtons);
    connect(m_list, &QTreeWidget::itemDoubleClicked, m_recover, &QPushButton::click);

    auto* layout = new QVBoxLayout(this);
    layout->addWidget(text);
    layout->addWidget(m_list);
    layout->addWidget(buttons);
    resize(640, 320);
    updateButtons();
}

void RecoveryDialog::updateButtons() {
    const bool any = m_list->currentItem() != nullptr;
    m_recover->setEnabled(any);
    m_discard->setEnabled(any);
}

} // namespace velvet::ui
