// Issue 17, items 11 and 12, driven through the real MainWindow under xvfb-run:
// - a plain start lists every recoverable autosave (saved documents and an untitled one) with its
//   document and time in the recovery dialog; Recover makes the chosen one the document, Discard
//   removes one, Later keeps the rest; stale autosaves (document saved since) are not listed;
// - the prompt for an untitled document's autosave does not say "newer than the saved file";
// - autosaves keep no "*.autosave.json.bak", and a clean exit removes those left behind;
// - File > Open Recent shows a file right after Save As and after the first Save of a new file.
#include "core/material.h"
#include "ui/autosave.h"
#include "ui/document_controller.h"
#include "ui/main_window.h"
#include "ui/recovery_dialog.h"
#include "ui/viewport_widget.h"
#include "ui_test_modal.h"
#include "ui_test_window.h"

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QFileDialog>
#include <QMenu>
#include <QMessageBox>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QTreeWidget>
#include <QUndoStack>
#include <functional>

using namespace velvet;
using namespace velvet::ui;
using velvet::test::answerFileDialog;
using velvet::test::onNextModal;

namespace {

/// Writes an autosave of @p file (empty: untitled) with roughness @p roughness, then drops the
/// controller without a clean exit: what a killed Velvet leaves behind.
bool leaveAutosave(const QString& file, float roughness) {
    DocumentController doc;
    if (!file.isEmpty()) {
        QStringList problems;
        if (!doc.openFile(file, &problems))
            return false;
    }
    doc.editParam(ParamId::Roughness, glm::vec3(roughness));
    Autosave autosave(&doc);
    return autosave.saveNow();
}

QStringList rowTexts(QTreeWidget* list, int column) {
    QStringList texts;
    for (int i = 0; i < list->topLevelItemCount(); ++i)
        texts << list->topLevelItem(i)->text(column);
    return texts;
}

} // namespace

class TestUiRecovery : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void cleanupTestCase();
    void init();

    void startupListsEveryRecoverableAutosave();
    void untitledPromptDoesNotClaimASavedFile();
    void recentMenuFollowsSaveAs();
    void cleanExitRemovesStaleBackups(); // last: it closes the window

private:
    /// A saved document with roughness @p roughness, in the temporary folder.
    QString savedDocument(const QString& name, float roughness);

    QTemporaryDir m_dir;
    std::unique_ptr<MainWindow> m_window;
    DocumentController* m_doc = nullptr;
};

void TestUiRecovery::initTestCase() {
    QVERIFY(m_dir.isValid());
    QDir(Autosave::directory()).removeRecursively(); // test mode: a throwaway folder
    QSettings().remove(QStringLiteral("files/recent"));
    m_window = std::make_unique<MainWindow>(/*restoreLayout=*/false);
    m_doc = m_window->controller();
    const QString error = test::showWithFirstFrame(m_window.get(), QSize(1280, 800));
    QVERIFY2(error.isEmpty(), qPrintable(error));
}

void TestUiRecovery::cleanupTestCase() {
    if (m_window) {
        m_doc->newDocument();
        m_window->close();
        m_window.reset();
    }
}

void TestUiRecovery::init() {
    m_doc->newDocument();
}

QString TestUiRecovery::savedDocument(const QString& name, float roughness) {
    DocumentController doc;
    doc.editParam(ParamId::Roughness, glm::vec3(roughness));
    const QString path = m_dir.filePath(name);
    QString error;
    if (!doc.saveAs(path, &error))
        qWarning("%s", qPrintable(error));
    return QFileInfo(path).absoluteFilePath();
}

void TestUiRecovery::startupListsEveryRecoverableAutosave() {
    const QString a = savedDocument(QStringLiteral("alpha.json"), 0.2f);
    const QString b = savedDocument(QStringLiteral("beta.json"), 0.3f);
    const QString stale = savedDocument(QStringLiteral("stale.json"), 0.4f);
    QTest::qWait(20); // autosaves newer than their files
    QVERIFY(leaveAutosave(a, 0.61f));
    QVERIFY(leaveAutosave(b, 0.72f));
    QVERIFY(leaveAutosave(QString(), 0.83f));
    QVERIFY(leaveAutosave(stale, 0.94f));
    // stale.json saved after its autosave was written: nothing to recover there.
    QFile staleFile(stale);
    QVERIFY(staleFile.open(QIODevice::ReadWrite));
    QVERIFY(staleFile.setFileTime(QDateTime::currentDateTime().addSecs(60),
                                  QFileDevice::FileModificationTime));
    staleFile.close();

    // The start-up list, answered in the real dialog: beta is recovered.
    QStringList documents, folders, times;
    onNextModal<RecoveryDialog>([&](RecoveryDialog* dialog) {
        auto* list = dialog->findChild<QTreeWidget*>(QStringLiteral("recoveryList"));
        documents = rowTexts(list, 0);
        folders = rowTexts(list, 1);
        times = rowTexts(list, 2);
        const int row = int(documents.indexOf(QStringLiteral("beta.json")));
        if (row < 0) {
            dialog->reject();
            return;
        }
        QTreeWidgetItem* item = list->topLevelItem(row);
        list->scrollToItem(item);
        QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier,
                          list->visualItemRect(item).center());
        QTest::mouseClick(dialog->findChild<QPushButton*>(QStringLiteral("recoverButton")),
                          Qt::LeftButton);
    });
    QVERIFY(m_window->autosave()->offerStartupRecovery(m_window.get()));
    documents.sort();
    QCOMPARE(documents, (QStringList{QStringLiteral("Untitled document"),
                                     QStringLiteral("alpha.json"), QStringLiteral("beta.json")}));
    QVERIFY(
        folders.contains(QDir::toNativeSeparators(m_dir.path())) ||
        folders.contains(QDir::toNativeSeparators(QFileInfo(m_dir.path()).canonicalFilePath())));
    for (const QString& time : times)
        QVERIFY2(!time.isEmpty(), "every row says when it was autosaved");
    QCOMPARE(m_doc->filePath(), b);
    QVERIFY(m_doc->isDirty());
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.72f);

    // Next start: beta is the document's own now; the untitled one is discarded, alpha is left
    // for later.
    onNextModal<RecoveryDialog>([&](RecoveryDialog* dialog) {
        auto* list = dialog->findChild<QTreeWidget*>(QStringLiteral("recoveryList"));
        documents = rowTexts(list, 0);
        const int row = int(documents.indexOf(QStringLiteral("Untitled document")));
        if (row >= 0) {
            QTreeWidgetItem* item = list->topLevelItem(row);
            QTest::mouseClick(list->viewport(), Qt::LeftButton, Qt::NoModifier,
                              list->visualItemRect(item).center());
            QTest::mouseClick(dialog->findChild<QPushButton*>(QStringLiteral("discardButton")),
                              Qt::LeftButton);
        }
        QCOMPARE(list->topLevelItemCount(), 1);
        QTest::mouseClick(dialog->findChild<QPushButton*>(QStringLiteral("laterButton")),
                          Qt::LeftButton);
    });
    QVERIFY(!m_window->autosave()->offerStartupRecovery(m_window.get()));
    documents.sort();
    QCOMPARE(documents,
             (QStringList{QStringLiteral("Untitled document"), QStringLiteral("alpha.json")}));
    QVERIFY(!QFile::exists(Autosave::autosavePathFor(QString())));
    QVERIFY(QFile::exists(Autosave::autosavePathFor(a)));
    QCOMPARE(m_doc->filePath(), b); // Later changed nothing
    const QList<Autosave::Recoverable> left = m_window->autosave()->recoverable();
    QCOMPARE(left.size(), 1);
    QCOMPARE(left[0].documentPath, a);

    // Opening alpha offers its autosave (the per-file path); declined, it is gone.
    onNextModal<QMessageBox>(
        [](QMessageBox* box) { QTest::mouseClick(box->button(QMessageBox::No), Qt::LeftButton); });
    m_doc->newDocument();
    QVERIFY(m_window->openFile(a));
    QVERIFY(m_window->autosave()->recoverable().isEmpty());
}

void TestUiRecovery::untitledPromptDoesNotClaimASavedFile() {
    QVERIFY(leaveAutosave(QString(), 0.55f));
    QString text;
    onNextModal<QMessageBox>([&text](QMessageBox* box) {
        text = box->text();
        QTest::mouseClick(box->button(QMessageBox::Yes), Qt::LeftButton);
    });
    QVERIFY(m_window->autosave()->offerRecovery(QString()));
    QVERIFY2(text.contains(QStringLiteral("untitled document")), qPrintable(text));
    QVERIFY2(!text.contains(QStringLiteral("saved file")), qPrintable(text));
    QCOMPARE(m_doc->material().scalar(ParamId::Roughness), 0.55f);
    QVERIFY(m_doc->filePath().isEmpty());

    // A saved document's prompt does say so.
    const QString file = savedDocument(QStringLiteral("gamma.json"), 0.1f);
    QTest::qWait(20);
    QVERIFY(leaveAutosave(file, 0.66f));
    onNextModal<QMessageBox>([&text](QMessageBox* box) {
        text = box->text();
        QTest::mouseClick(box->button(QMessageBox::No), Qt::LeftButton);
    });
    QVERIFY(!m_window->autosave()->offerRecovery(file));
    QVERIFY2(text.contains(QStringLiteral("gamma.json")) &&
                 text.contains(QStringLiteral("newer than the saved file")),
             qPrintable(text));
    m_window->autosave()->discard();
}

void TestUiRecovery::recentMenuFollowsSaveAs() {
    auto* recent = m_window->findChild<QMenu*>(QStringLiteral("recentMenu"));
    QVERIFY(recent);
    QSettings().remove(QStringLiteral("files/recent"));
    // The menu as the window has it now (empty: disabled), without opening it.
    QMetaObject::invokeMethod(recent, "aboutToShow");
    QVERIFY(!recent->isEnabled());

    // The first Ctrl+S of a new document asks where to save.
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.31f));
    const QString first = m_dir.filePath(QStringLiteral("first-save.json"));
    answerFileDialog(first);
    QVERIFY(test::activate(m_window.get()));
    QTest::keyClick(m_window.get(), Qt::Key_S, Qt::ControlModifier);
    QTRY_COMPARE(m_doc->filePath(), QFileInfo(first).absoluteFilePath());
    QVERIFY(recent->isEnabled());
    QVERIFY(!recent->actions().isEmpty());
    QCOMPARE(recent->actions().first()->text(), QStringLiteral("first-save.json"));

    // Save As under another name: at the top of the menu at once.
    const QString second = m_dir.filePath(QStringLiteral("saved-as.json"));
    answerFileDialog(second);
    QVERIFY(test::activate(
        m_window.get())); // no window manager under xvfb gives the focus back after the dialog
    QTest::keyClick(m_window.get(), Qt::Key_S, Qt::ControlModifier | Qt::ShiftModifier);
    QTRY_COMPARE(m_doc->filePath(), QFileInfo(second).absoluteFilePath());
    QStringList names;
    for (QAction* act : recent->actions())
        if (!act->isSeparator())
            names << act->text();
    QCOMPARE(names, (QStringList{QStringLiteral("saved-as.json"), QStringLiteral("first-save.json"),
                                 QStringLiteral("Clear Menu")}));
}

void TestUiRecovery::cleanExitRemovesStaleBackups() {
    // Two autosaves of one document: the second replaces the first and keeps no backup.
    const QString file = savedDocument(QStringLiteral("delta.json"), 0.1f);
    QVERIFY(m_window->openFile(file));
    QTest::qWait(20);
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.2f));
    QVERIFY(m_window->autosave()->saveNow());
    m_doc->editParam(ParamId::Roughness, glm::vec3(0.3f));
    QVERIFY(m_window->autosave()->saveNow());
    const QString autosave = Autosave::autosavePathFor(file);
    QVERIFY(QFile::exists(autosave));
    QVERIFY(!QFile::exists(autosave + QStringLiteral(".bak")));

    // One an earlier Velvet left behind.
    const QString leftover =
        QDir(Autosave::directory()).filePath(QStringLiteral("old-0123456789ab.autosave.json.bak"));
    {
        QFile f(leftover);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("{}");
    }
    // A clean exit (the changes discarded in the prompt).
    onNextModal<QMessageBox>([](QMessageBox* box) {
        QTest::mouseClick(box->button(QMessageBox::Discard), Qt::LeftButton);
    });
    QVERIFY(m_window->close());
    QVERIFY(!QFile::exists(leftover));
    QVERIFY(!QFile::exists(autosave));
    // stale.json's autosave (its document saved since, never offered) went too.
    QCOMPARE(QDir(Autosave::directory()).entryList({QStringLiteral("stale-*")}, QDir::Files),
             QStringList());
    QCOMPARE(QDir(Autosave::directory())
                 .entryList({QStringLiteral("*.bak"), QStringLiteral("*.source")}, QDir::Files),
             QStringList());
    m_window.reset();
}

int main(int argc, char** argv) {
    QStandardPaths::setTestModeEnabled(true); // QSettings and autosaves go to a throwaway place
    QSurfaceFormat::setDefaultFormat(ViewportWidget::requiredFormat());
    QApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QApplication app(argc, argv);
    QApplication::setApplicationName(QStringLiteral("VelvetRecoveryTest"));
    QApplication::setOrganizationName(QStringLiteral("VelvetTest"));
    TestUiRecovery test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_ui_recovery.moc"
