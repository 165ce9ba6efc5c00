#pragma once
/// @file main_window.h
/// The editor window: the viewport in the centre with its toolbars (view state; scene mesh and
/// environment), docks around it (Properties, Scene, History, Log, …), the File, Edit and View
/// menus, recent files, drag and drop of scenes, presets, HDRIs and meshes, a status bar with the
/// frame time and environment progress, and the dirty-document prompt on close.

#include "core/material.h"

#include <QMainWindow>
#include <QStringList>
#include <memory>
#include <optional>

class QAction;
class QLabel;
class QMenu;
class QUndoView;

namespace velvet {
class ColorManagement;
}

namespace velvet::ui {

class AbSplitControl;
class AtlasPanel;
class ScenePanel;
class Autosave;
class DocumentController;
class LibraryPanel;
class ReferencePanel;
class LogPanel;
class PostChainPanel;
class PropertyPanel;
class SceneToolbar;
class ViewportToolbar;
class ViewportWidget;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    /// @p restoreLayout: restore geometry, dock state and view state from QSettings and save
    /// them on close (off for screenshots and tests that need the defaults).
    explicit MainWindow(bool restoreLayout = true, QWidget* parent = nullptr);
    ~MainWindow() override;

    /// Bump when docks or toolbars are added or renamed (QMainWindow::saveState's version).
    static constexpr int kLayoutVersion = 5;
    /// At most this many entries in File > Open Recent.
    static constexpr int kMaxRecentFiles = 8;

    DocumentController* controller() const { return m_controller; }
    ViewportWidget* viewport() const { return m_viewport; }
    PropertyPanel* propertyPanel() const { return m_properties; }
    LogPanel* logPanel() const { return m_log; }
    PostChainPanel* postChainPanel() const { return m_postChain; }
    LibraryPanel* libraryPanel() const { return m_library; }
    ReferencePanel* referencePanel() const { return m_reference; }
    ViewportToolbar* viewportToolbar() const { return m_viewToolbar; }
    SceneToolbar* sceneToolbar() const { return m_sceneToolbar; }
    AtlasPanel* atlasPanel() const { return m_atlas; }
    ScenePanel* scenePanel() const { return m_scene; }
    Autosave* autosave() const { return m_autosave; }
    /// The toolbar's A/B split toggle.
    QAction* abSplitAction() const;
    /// The A/B split's toolbar button, menu and swap shortcut.
    AbSplitControl* abSplit() const { return m_abSplit; }

    /// Opens @p path, showing problems in a message box and the Log. False when it could not be
    /// opened. Successful opens go to the recent files.
    bool openFile(const QString& path);
    /// A file dropped onto the window: .json opens (after the dirty prompt), .exr/.hdr becomes
    /// the HDRI and a mesh file the custom preview mesh (both undoable). False when the type is
    /// not handled or the open failed.
    bool openDroppedFile(const QString& path);

    /// File > Open Recent, newest first (QSettings, at most kMaxRecentFiles).
    static QStringList recentFiles();
    static void addRecentFile(const QString& path);

public slots:
    void newDocument();
    void openDocument();
    bool saveDocument();
    bool saveDocumentAs();
    /// T: recompiles the shaders from disk; errors (file:line) go to the Log, the last good
    /// programs keep drawing.
    bool reloadShaders();
    /// R: reads the document's file again (asks first when there are unsaved changes).
    bool reloadScene();
    /// A/B split on: B is a snapshot of the current material (or @p b when given); off: one
    /// material. View state only.
    void setAbSplit(bool on, std::optional<Material> b = std::nullopt);
    /// A/B split with B = the current material with BRDF term @p term (a choice parameter:
    /// distribution, visibility, Fresnel, diffuse, sheen model) set to @p choice.
    void setAbSplitTerm(ParamId term, int choice);
    /// Loads a material preset as B and turns the split on. False when it could not be read.
    bool setAbSplitPreset(const QString& path);

protected:
    void closeEvent(QCloseEvent* event) override;
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void createDocks();
    void createToolbars();
    void createMenus();
    void updateTitle();
    void fillRecentMenu();
    /// Asks whether to save a dirty document. False when the artist cancels.
    bool maybeSave();
    void showFrameTime(double cpuMs);
    void applyViewState();
    void rotateEnvironment(float deltaDeg, int gestureKey);

    std::shared_ptr<const ColorManagement> m_colorManagement;
    DocumentController* m_controller;
    ViewportWidget* m_viewport;
    PropertyPanel* m_properties = nullptr;
    QUndoView* m_history = nullptr;
    LogPanel* m_log = nullptr;
    PostChainPanel* m_postChain = nullptr;
    LibraryPanel* m_library = nullptr;
    ReferencePanel* m_reference = nullptr;
    ViewportToolbar* m_viewToolbar = nullptr;
    SceneToolbar* m_sceneToolbar = nullptr;
    AtlasPanel* m_atlas = nullptr;
    ScenePanel* m_scene = nullptr;
    Autosave* m_autosave = nullptr;
    AbSplitControl* m_abSplit = nullptr;
    QMenu* m_recentMenu = nullptr;
    QLabel* m_frameLabel = nullptr;
    QLabel* m_progressLabel = nullptr;
    QLabel* m_textureLabel = nullptr; // textures loading: "Loading textures: 1 of 3 · 40 %"
    bool m_saveLayout;
};

} // namespace velvet::ui
