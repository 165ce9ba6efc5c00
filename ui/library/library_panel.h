#pragma once
/// @file library_panel.h
/// The material Library (issue 5): the shipped presets (resources/presets) and the user's
/// (QStandardPaths::AppDataLocation/presets) in an icon grid with thumbnails rendered in the
/// background by ThumbnailRenderer (a placeholder until each is ready), a search field that
/// filters by name and tag, Apply (or double click) as one undoable command, and "Save current
/// material as preset…" with a name and tags.

#include <QIcon>
#include <QString>
#include <QStringList>
#include <QWidget>

class QLineEdit;
class QListView;
class QPushButton;
class QSortFilterProxyModel;
class QStandardItem;
class QStandardItemModel;

namespace velvet::ui {

class DocumentController;
class ThumbnailRenderer;

class LibraryPanel : public QWidget {
    Q_OBJECT
public:
    enum Role {
        PathRole = Qt::UserRole + 1, ///< the preset file (QString)
        TagsRole,                    ///< its tags (QStringList)
        SearchRole,                  ///< name and tags, what the search field matches
        UserPresetRole,              ///< true for the user's presets
        ThumbnailReadyRole,          ///< true once the rendered thumbnail replaced the placeholder
        SortRole,                    ///< the list order: fabrics first, then leather, then the rest
    };

    struct Options {
        /// Folders of shipped presets; empty: resources/presets.
        QStringList presetDirs;
        /// The user's presets; empty: QStandardPaths::AppDataLocation/presets.
        QString userDir;
        /// Thumbnail cache; empty: QStandardPaths::CacheLocation/thumbnails.
        QString cacheDir;
    };

    explicit LibraryPanel(DocumentController* controller, QWidget* parent = nullptr);
    LibraryPanel(DocumentController* controller, const Options& options, QWidget* parent = nullptr);
    ~LibraryPanel() override;

    QListView* view() const { return m_view; }
    QLineEdit* searchField() const { return m_search; }
    /// Every preset, unfiltered.
    QStandardItemModel* model() const { return m_model; }
    /// What the grid shows (the search applied).
    QSortFilterProxyModel* filteredModel() const { return m_proxy; }
    ThumbnailRenderer* thumbnails() const { return m_thumbnails; }
    QString userDir() const { return m_userDir; }

    /// Reads the preset folders again (keeps thumbnails already made).
    void reload();
    /// Asks for every missing thumbnail. Happens on the first show (a hidden Library tab renders
    /// nothing, so windows and tests that never show it pay nothing).
    void requestThumbnails();
    /// Number of presets whose thumbnail is still the placeholder.
    int placeholderCount() const;
    /// The row of the preset named @p name in model(), or -1.
    int rowOfName(const QString& name) const;

    /// Applies the preset at @p path: one undoable command replacing the material. False +
    /// @p error when it cannot be read.
    bool applyPreset(const QString& path, QString* error = nullptr);
    /// Saves the document's material as a user preset named @p name with @p tags (file name
    /// from the name) and lists it. False + @p error on failure.
    bool saveUserPreset(const QString& name, const QStringList& tags, QString* error = nullptr);

public slots:
    /// Applies the selected preset (the Apply button).
    void applySelected();
    /// Asks for a name and tags, then saveUserPreset.
    void saveUserPresetDialog();

signals:
    /// Errors for the Log, already formatted.
    void problemsReported(const QString& text);

protected:
    void showEvent(QShowEvent* event) override;

private:
    void init(const Options& options);
    QStandardItem* addPresetItem(const QString& path, bool user);
    void onThumbnail(const QString& path, const QImage& image);

    DocumentController* m_controller;
    QStringList m_presetDirs;
    QString m_userDir;
    QStandardItemModel* m_model = nullptr;
    QSortFilterProxyModel* m_proxy = nullptr;
    QListView* m_view = nullptr;
    QLineEdit* m_search = nullptr;
    QPushButton* m_apply = nullptr;
    ThumbnailRenderer* m_thumbnails = nullptr;
    QIcon m_placeholder;
    bool m_thumbnailsActive = false; ///< set on the first show
};

} // namespace velvet::ui
