#pragma once
/// @file document_controller.h
/// The open document as the editor sees it: the Scene, its file, its undo stack and dirty state.
/// Panels edit through the controller (edit* functions push a QUndoCommand); commands apply their
/// change through the set* functions; views listen to the signals.

#include "core/atlas_document.h"
#include "core/scene.h"
#include "core/scene_parts.h"

#include <QObject>
#include <QString>
#include <QStringList>
#include <glm/vec3.hpp>

class QUndoStack;

namespace velvet::ui {

class DocumentController : public QObject {
    Q_OBJECT
public:
    explicit DocumentController(QObject* parent = nullptr);
    ~DocumentController() override;

    /// @name The document
    /// @{
    const Scene& scene() const { return m_scene; }
    const Material& material() const { return m_scene.material; }
    glm::vec3 param(ParamId id) const { return m_scene.material.value(id); }
    /// The file the document was read from or last saved to; empty for a new document.
    QString filePath() const { return m_filePath; }
    /// The file name shown in the title ("Untitled" for a new document).
    QString displayName() const;
    QUndoStack* undoStack() const { return m_undoStack; }
    /// True when the undo stack is not at its clean index.
    bool isDirty() const;
    /// The document's atlases (core/atlas_document.h). Saved beside the scene file as
    /// "<scene name>.atlas.json", which the scene names (Scene::atlases), and read with it.
    const AtlasSet& atlases() const { return m_atlases; }
    /// @}

    /// @name Edits from panels (each pushes one undoable command)
    /// @{
    /// Sets a parameter. Edits sharing a non-zero @p mergeKey (one slider drag) and the same
    /// parameter merge into one command. Does nothing when the value would not change.
    void editParam(ParamId id, glm::vec3 value, int mergeKey = 0);
    /// Puts a parameter back to its metadata default (one command, "Reset <label>").
    void resetParam(ParamId id);
    /// Replaces the environment (HDRI, intensity, rotation, …). Edits sharing a non-zero
    /// @p mergeKey (one drag) merge into one command named @p text. No-op edits push nothing.
    void editEnvironment(const Environment& environment, const QString& text, int mergeKey = 0);
    /// Replaces the preview mesh (one command). No-op edits push nothing. A custom mesh file is
    /// imported first (core's importMesh, in a child process): one that cannot be imported is
    /// refused — no command, the document keeps its mesh — and false comes back with the reason
    /// in @p error (also sent as meshRefused). The document never names a mesh it cannot show.
    bool editMesh(const MeshRef& mesh, QString* error = nullptr);
    /// Replaces the scene's lights (one command named @p text: a light added, removed or edited,
    /// a rig applied). Edits sharing a non-zero @p mergeKey (one spin-box or slider gesture)
    /// merge. No-op edits push nothing.
    void editLights(const std::vector<Light>& lights, const QString& text, int mergeKey = 0);
    /// Fills a material texture slot (one command named @p text). No-op edits push nothing.
    void editTexture(TextureSlot slot, const TextureRef& ref, const QString& text);
    /// An image the artist puts into an empty colour slot (a drop, a file chosen): the slot's
    /// colour factor multiplies the map (glTF), so a dark factor would hide it; the factor goes to
    /// white in the same undo step so the map shows as painted, as Blender and Substance show an
    /// image connected to a colour. Other slots, or a slot that had a map, are editTexture().
    /// Returns true when the factor was reset (the caller may say so).
    bool assignTextureImage(TextureSlot slot, const TextureRef& ref, const QString& text);
    /// @}

    /// @name Applied by undo commands (not undoable by themselves)
    /// @{
    /// Sets a parameter (clamped to its hard range by Material) and notifies (paramChanged,
    /// sceneChanged: MaterialValues).
    void setParam(ParamId id, glm::vec3 value);
    /// Sets the environment and notifies (sceneChanged: Environment).
    void setEnvironment(const Environment& environment);
    /// Sets the preview mesh and notifies (sceneChanged: Mesh).
    void setMesh(const MeshRef& mesh);
    /// Sets the lights and notifies (sceneChanged: Lights).
    void setLights(const std::vector<Light>& lights);
    /// Sets the material's node graph and notifies (sceneChanged: Graph only: the graph editor's
    /// model, ui/models/graph_model.h, is the one caller and already knows).
    void setMaterialGraph(const SharedGraph& graph);
    /// Sets a texture slot and notifies (sceneChanged: MaterialStructure).
    void setTexture(TextureSlot slot, const TextureRef& ref);
    /// Replaces the post chain and notifies (postChainChanged, sceneChanged: PostChain).
    void setPostChain(const PostChain& chain);
    /// Keeps the viewport's camera (the artist's orbit) with the document, so that a save
    /// writes it and a reopen shows that view again. View state: no undo step, not dirty, no
    /// signal (the viewport that reports it already draws it).
    void setViewCamera(const Camera& camera) { m_scene.camera = camera; }
    /// Replaces one atlas and notifies (atlasChanged, sceneChanged: Atlases).
    void setAtlas(AtlasKind kind, AtlasDocument atlas);
    /// Replaces the whole material (a library preset) and where it came from; notifies
    /// (paramChanged for every parameter, materialReplaced, sceneChanged).
    void setMaterial(const Material& material, const std::string& preset);
    /// @}

    /// @name Whole documents (clear the undo stack; never half-applied)
    /// @{
    /// Replaces the document with the built-in default scene.
    void newDocument();
    /// Opens a scene, or a material preset shown in the default scene. On failure the current
    /// document is untouched and @p problems gets one "file: path: message" line per problem.
    bool openFile(const QString& path, QStringList* problems);
    /// Saves to filePath() (which must not be empty). False + @p error on failure.
    bool save(QString* error);
    /// Saves as a scene to @p path and makes it the document's file. False + @p error on failure.
    bool saveAs(const QString& path, QString* error);
    /// Takes @p scene (and its atlases) as a new, clean document (used by newDocument/openFile
    /// and tests).
    void setDocument(Scene scene, const QString& filePath, AtlasSet atlases = {});
    /// Takes @p scene as the document of @p filePath with unsaved changes (crash recovery: the
    /// undo stack is empty and the document is dirty until saved).
    void setRecoveredDocument(Scene scene, const QString& filePath);
    /// @}

signals:
    /// Parts of the scene changed (core/scene_parts.h): one bit for a parameter, a light list or
    /// a mesh edit, ScenePart::Material for a preset, ScenePart::All for a new or opened document.
    /// Views update only what @p parts names (the renderer uploads only those parts).
    void sceneChanged(velvet::ScenePart parts);
    /// One material parameter changed (undo, redo or edit).
    void paramChanged(velvet::ParamId id);
    /// The post chain changed (an effect added, removed, moved, toggled or edited; undo, redo).
    void postChainChanged();
    /// One atlas changed (an edit, undo, redo; every kind on new and open).
    void atlasChanged(velvet::AtlasKind kind);
    /// The whole material was replaced (a library preset applied, or its undo).
    void materialReplaced();
    /// The whole document was replaced (new or open); views reset their view state.
    void documentReplaced();
    /// The file path or display name changed.
    void fileChanged(const QString& filePath);
    /// The undo stack left or reached its clean state.
    void dirtyChanged(bool dirty);
    /// editMesh refused a mesh file: @p message names the file and the reason.
    void meshRefused(const QString& message);

public:
    /// @name Post chain edits, effects addressed by id (EffectInstance::id), so an edit reaches
    /// the same effect after a reorder. Values go through core's rules (setEffectParam: clamped,
    /// a choice rounded); each edit is one undo command, and consecutive edits with the same
    /// non-zero @p mergeKey (one slider drag) merge into one. False when nothing changes (an
    /// unknown effect or parameter, or the value it already holds).
    /// @{
    bool editEffectParam(EffectId effect, const std::string& param, glm::vec3 value,
                         int mergeKey = 0);
    /// Back to the parameter's default: one command named "Reset <effect> <parameter>".
    bool resetEffectParam(EffectId effect, const std::string& param);
    /// @}

private:
    Scene m_scene;
    AtlasSet m_atlases;
    QString m_filePath;
    QUndoStack* m_undoStack = nullptr;
};

} // namespace velvet::ui
