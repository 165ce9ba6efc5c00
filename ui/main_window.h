#pragma once
/// @file main_window.h
/// The editor window: the viewport in the centre, docks around it (Properties, History), the File
/// and Edit menus, a status bar with the frame time, and the dirty-document prompt on close.

#include <QMainWindow>

class QLabel;
class QUndoView;

namespace velvet::ui {

class DocumentController;
class PropertyPanel;
class ViewportWidget;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    /// @p restoreLayout: restore geometry and dock state from QSettings (off for screenshots).
    explicit MainWindow(bool restoreLayout = true, QWidget* parent = nullptr);
    ~MainWindow() override;

    DocumentController* controller() const { return m_controller; }
    ViewportWidget* viewport() const { return m_viewport; }
    PropertyPanel* propertyPanel() const { return m_properties; }

    /// Opens @p path, showing problems in a message box. False when it could not be opened.
    bool openFile(const QString& path);

public slots:
    void newDocument();
    void openDocument();
    bool saveDocument();
    bool saveDocumentAs();

protected:
    void closeEvent(QCloseEvent* event) override;

private:
    void createDocks();
    void createMenus();
    void updateTitle();
    /// Asks whether to save a dirty document. False when the artist cancels.
    bool maybeSave();
    void showFrameTime(double cpuMs);

    DocumentController* m_controller;
    ViewportWidget* m_viewport;
    PropertyPanel* m_properties = nullptr;
    QUndoView* m_history = nullptr;
    QLabel* m_frameLabel = nullptr;
    bool m_saveLayout;
};

} // namespace velvet::ui
