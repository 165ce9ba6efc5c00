#include "ui/document_controller.h"

#include "core/default_stage.h"
#include "core/document_io.h"
#include "core/mesh_import.h"
#include "core/post_effects.h"
#include "core/scene_document.h"
#include "ui/busy_work.h"
#include "ui/commands/atlas_commands.h"
#include "ui/commands/post_chain_commands.h"
#include "ui/commands/set_param_command.h"
#include "ui/commands/set_scene_command.h"

#include <QFileInfo>
#include <QUndoStack>
#include <optional>

namespace velvet::ui {
namespace {

std::filesystem::path toPath(const QString& path) {
    return std::filesystem::path(path.toStdString());
}

QStringList problemLines(const Problems& problems, const QString& file) {
    QStringList lines;
    for (const Problem& p : problems.items)
        if (p.severity == Problem::Severity::Error)
            lines << QString::fromStdString(p.toString());
    if (lines.isEmpty())
        lines << QStringLiteral("%1: could not be read").arg(file);
    return lines;
}

} // namespace

DocumentController::DocumentController(QObject* parent)
    : QObject(parent), m_undoStack(new QUndoStack(this)) {
    connect(m_undoStack, &QUndoStack::cleanChanged, this,
            [this](bool clean) { emit dirtyChanged(!clean); });
}

DocumentController::~DocumentController() {
    // The undo stack is a child, which ~QObject would delete after this class is gone; its
    // clear() then emitted indexChanged to receivers that call back into this half-destroyed
    // object (Autosave's debounce asked isDirty(): UBSan's vptr check, make test-asan). Deleted
    // here, while the controller is whole, and silently: nothing is edited any more.
    m_undoStack->blockSignals(true);
    delete m_undoStack;
    m_undoStack = nullptr;
}

QString DocumentController::displayName() const {
    return m_filePath.isEmpty() ? tr("Untitled") : QFileInfo(m_filePath).fileName();
}

bool DocumentController::isDirty() const {
    return !m_undoStack->isClean();
}

void DocumentController::editParam(ParamId id, glm::vec3 value, int mergeKey) {
    // Compare against what the model would store, so a no-op edit (clamped, or the same value)
    // never creates a command.
    Material probe = m_scene.material;
    probe.setValue(id, value);
    if (probe.value(id) == m_scene.material.value(id))
        return;
    m_undoStack->push(
        new SetParamCommand(this, id, m_scene.material.value(id), probe.value(id), mergeKey));
}

void DocumentController::resetParam(ParamId id) {
    const glm::vec3 def = paramMeta(id).defaultValue;
    if (m_scene.material.value(id) == def)
        return;
    auto* cmd = new SetParamCommand(this, id, m_scene.material.value(id), def, 0);
    cmd->setText(tr("Reset %1").arg(QString::fromUtf8(paramMeta(id).label)));
    m_undoStack->push(cmd);
}

void DocumentController::editEnvironment(const Environment& environment, const QString& text,
                                         int mergeKey) {
    if (environment == m_scene.environment)
        return;
    m_undoStack->push(
        new SetEnvironmentCommand(this, m_scene.environment, environment, text, mergeKey));
}

bool DocumentController::editMesh(const MeshRef& mesh, QString* error) {
    if (mesh == m_scene.mesh)
        return true;
    // Import before the edit rather than let the renderer find out (it would draw the sphere
    // while History and the saved file named the broken file, issue 17 item 13). The renderer
    // imports once more when it draws: an import is a fraction of a second for a preview mesh.
    if (mesh.kind == PreviewMeshKind::Custom) {
        MeshData data;
        std::string reason;
        const QString name = QFileInfo(QString::fromStdString(mesh.file)).fileName();
        // In its child process, waited for off the UI thread: a large file (or a hostile one,
        // up to the importer's 10 s limit) never freezes the window (issue 18).
        const bool ok = mesh.file.empty()
                            ? (reason = "no file given", false)
                            : runWithBusyDialog(tr("Importing the mesh %1…").arg(name), [&] {
                                  return importMesh(mesh.file, data, &reason);
                              });
        if (!ok) {
            const QString message =
                tr("Mesh %1 refused, the mesh is unchanged: %2")
                    .arg(name.isEmpty() ? tr("(none)") : name, QString::fromStdString(reason));
            if (error)
                *error = message;
            emit meshRefused(message);
            return false;
        }
    }
    m_undoStack->push(new SetMeshCommand(this, m_scene.mesh, mesh));
    return true;
}

void DocumentController::editLights(const std::vector<Light>& lights, const QString& text,
                                    int mergeKey) {
    if (lights == m_scene.lights)
        return;
    m_undoStack->push(new SetLightsCommand(this, m_scene.lights, lights, text, mergeKey));
}

void DocumentController::editTexture(TextureSlot slot, const TextureRef& ref, const QString& text) {
    if (m_scene.material.texture(slot) == ref)
        return;
    m_undoStack->push(new SetTextureCommand(this, slot, m_scene.material.texture(slot), ref, text));
}

bool DocumentController::assignTextureImage(TextureSlot slot, const TextureRef& ref,
                                            const QString& text) {
    const auto factorOf = [](TextureSlot s) -> std::optional<ParamId> {
        switch (s) {
        case TextureSlot::BaseColor:
            return ParamId::BaseColor;
        case TextureSlot::Emissive:
            return ParamId::EmissiveColor;
        case TextureSlot::SheenColor:
            return ParamId::SheenColor;
        case TextureSlot::SpecularColor:
            return ParamId::SpecularColor;
        default:
            return std::nullopt;
        }
    };
    const std::optional<ParamId> factor = factorOf(slot);
    const bool wasEmpty = m_scene.material.texture(slot).empty();
    if (!factor || !wasEmpty || ref.empty() || m_scene.material.color(*factor) == glm::vec3(1.0f)) {
        editTexture(slot, ref, text);
        return false;
    }
    m_undoStack->beginMacro(text);
    editTexture(slot, ref, text);
    editParam(*factor, glm::vec3(1.0f));
    m_undoStack->endMacro();
    return true;
}

void DocumentController::setTexture(TextureSlot slot, const TextureRef& ref) {
    m_scene.material.setTexture(slot, ref);
    emit sceneChanged(ScenePart::MaterialStructure);
}

void DocumentController::setEnvironment(const Environment& environment) {
    m_scene.environment = environment;
    emit sceneChanged(ScenePart::Environment);
}

void DocumentController::setMesh(const MeshRef& mesh) {
    m_scene.mesh = mesh;
    emit sceneChanged(ScenePart::Mesh);
}

void DocumentController::setLights(const std::vector<Light>& lights) {
    m_scene.lights = lights;
    emit sceneChanged(ScenePart::Lights);
}

void DocumentController::setMaterialGraph(const SharedGraph& graph) {
    m_scene.material.graph = graph;
    emit sceneChanged(ScenePart::Graph);
}

void DocumentController::setPostChain(const PostChain& chain) {
    m_scene.post = chain;
    emit postChainChanged();
    emit sceneChanged(ScenePart::PostChain);
}

void DocumentController::setAtlas(AtlasKind kind, AtlasDocument atlas) {
    m_atlases[kind] = std::move(atlas);
    emit atlasChanged(kind);
    emit sceneChanged(ScenePart::Atlases);
}

void DocumentController::setMaterial(const Material& material, const std::string& preset) {
    m_scene.material = material;
    m_scene.materialPreset = preset;
    for (int i = 0; i < kParamCount; ++i)
        emit paramChanged(static_cast<ParamId>(i));
    emit materialReplaced();
    emit sceneChanged(ScenePart::Material);
}

void DocumentController::setParam(ParamId id, glm::vec3 value) {
    m_scene.material.setValue(id, value);
    emit paramChanged(id);
    emit sceneChanged(ScenePart::MaterialValues);
}

void DocumentController::newDocument() {
    Problems problems; // the default scene falls back silently; problems go to the log issue
    // The look-dev stage (core/default_stage.h): the HDRI's bright side behind the mesh, a
    // blurred background, the mesh framed.
    setDocument(stageScene(&problems), QString());
}

bool DocumentController::openFile(const QString& path, QStringList* problems) {
    Problems found;
    const std::filesystem::path file = toPath(path);
    std::optional<Scene> scene;
    const DocumentKind kind = detectDocumentKind(file);
    switch (kind) {
    case DocumentKind::Material:
        if (std::optional<Material> material = loadMaterialFile(file, found)) {
            // Shown on the look-dev stage, like a new document (core/default_stage.h).
            scene = stageSceneWithMaterial(std::move(*material));
            scene->materialPreset = file.string();
        }
        break;
    case DocumentKind::Scene:
    case DocumentKind::Unknown: // the scene loader reports what is wrong with the file
        scene = loadSceneFile(file, found);
        break;
    }
    // The scene's atlases are part of the document: a broken atlas file refuses the open, a
    // missing one is a warning (the scene reader's) and the scene opens without atlases.
    std::optional<AtlasSet> atlases = AtlasSet{};
    if (scene && !found.hasErrors() && !scene->atlases.empty()) {
        std::error_code ec;
        if (std::filesystem::exists(scene->atlases, ec))
            atlases = loadAtlasFile(scene->atlases, found);
    }
    if (!scene || !atlases || found.hasErrors()) {
        if (problems)
            *problems = problemLines(found, path);
        return false;
    }
    // A preset is not a scene: saving it writes a new scene file, never over the preset.
    const bool isPreset = kind == DocumentKind::Material;
    setDocument(std::move(*scene), isPreset ? QString() : QFileInfo(path).absoluteFilePath(),
                std::move(*atlases));
    return true;
}

bool DocumentController::save(QString* error) {
    if (m_filePath.isEmpty()) {
        if (error)
            *error = tr("The document has no file yet: use Save As.");
        return false;
    }
    return saveAs(m_filePath, error);
}

bool DocumentController::saveAs(const QString& path, QString* error) {
    // The atlases first, then the scene that names them, each write atomic: core's one way to
    // save a document, which the CLI shares (core/scene_document.h).
    Problems problems;
    std::optional<SceneDocument> saved =
        saveSceneDocument({m_scene, m_atlases}, toPath(path), problems);
    if (!saved) {
        if (error)
            *error = problems.items.empty()
                         ? QStringLiteral("%1: could not be saved").arg(path)
                         : QString::fromStdString(problems.items.front().toString());
        return false;
    }
    m_scene.atlases = saved->scene.atlases;
    m_atlases = std::move(saved->atlases); // sources now name their files
    const QString absolute = QFileInfo(path).absoluteFilePath();
    if (absolute != m_filePath) {
        m_filePath = absolute;
        emit fileChanged(m_filePath);
    }
    m_undoStack->setClean();
    return true;
}

void DocumentController::setDocument(Scene scene, const QString& filePath, AtlasSet atlases) {
    m_scene = std::move(scene);
    m_atlases = std::move(atlases);
    m_undoStack->clear(); // the old document's commands point at values that no longer exist
    m_undoStack->setClean();
    m_filePath = filePath;
    emit fileChanged(m_filePath);
    emit documentReplaced();
    emit postChainChanged();
    for (int k = 0; k < kAtlasKindCount; ++k)
        emit atlasChanged(AtlasKind(k));
    emit materialReplaced();
    emit sceneChanged(ScenePart::All);
    emit dirtyChanged(false);
}

} // namespace velvet::ui

namespace velvet::ui {

void DocumentController::setRecoveredDocument(Scene scene, const QString& filePath) {
    // The atlases as last saved (the autosave holds the scene only); unreadable: none.
    AtlasSet atlases;
    std::error_code ec;
    if (!scene.atlases.empty() && std::filesystem::exists(scene.atlases, ec)) {
        Problems problems;
        if (std::optional<AtlasSet> loaded = loadAtlasFile(scene.atlases, problems))
            atlases = std::move(*loaded);
    }
    setDocument(std::move(scene), filePath, std::move(atlases));
    m_undoStack->resetClean(); // no clean state on the stack: dirty until saved
    emit dirtyChanged(true);
}

bool DocumentController::editEffectParam(EffectId effect, const std::string& param, glm::vec3 value,
                                         int mergeKey) {
    // Compare against what core would store, so a no-op edit (clamped, or the same value) never
    // creates a command.
    PostChain probe = m_scene.post;
    if (!setEffectParam(probe, effect, param, value))
        return false;
    const size_t index = size_t(findEffectIndex(probe, effect));
    const EffectInstance& before = m_scene.post.effects[index];
    const EffectInstance& after = probe.effects[index];
    const ParamMeta& meta = *findEffectParam(*findPostEffect(after.type), param);
    if (effectValue(before, meta) == effectValue(after, meta))
        return false;
    const auto it = before.params.find(param);
    m_undoStack->push(new SetEffectParamCommand(
        this, effect, param, it == before.params.end() ? std::vector<float>{} : it->second,
        after.params.at(param), mergeKey));
    return true;
}

bool DocumentController::resetEffectParam(EffectId effect, const std::string& param) {
    const long index = findEffectIndex(m_scene.post, effect);
    const EffectMeta* meta =
        index < 0 ? nullptr : findPostEffect(m_scene.post.effects[size_t(index)].type);
    const ParamMeta* p = meta ? findEffectParam(*meta, param) : nullptr;
    if (!p)
        return false;
    const EffectInstance& current = m_scene.post.effects[size_t(index)];
    if (effectValue(current, *p) == p->defaultValue)
        return false;
    const auto it = current.params.find(param);
    auto* cmd = new SetEffectParamCommand(
        this, effect, param, it == current.params.end() ? std::vector<float>{} : it->second,
        effectParamComponents(*p, p->defaultValue), 0);
    cmd->setText(tr("Reset %1 %2")
                     .arg(QString::fromUtf8(meta->label.data(), qsizetype(meta->label.size())),
                          QString::fromUtf8(p->label.data(), qsizetype(p->label.size()))));
    m_undoStack->push(cmd);
    return true;
}

} // namespace velvet::ui
