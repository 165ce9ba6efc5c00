#pragma once
/// @file value_edit_command.h
/// The one merge rule of the commands that set one value (a slider, a spin box, a dragged region).

#include <QUndoCommand>
#include <utility>

namespace velvet::ui {

/// Base of a command that changes one value from m_old to m_new. Consecutive commands of one drag
/// merge into one (Qt's QUndoCommand::id()/mergeWith(), as QtNodes merges its node moves): the
/// same id() (Derived::kId), the same non-zero merge key and the same target
/// (Derived::sameTarget). A drag that ends where it began leaves nothing to undo, so the merged
/// command turns obsolete and the stack drops it.
///
/// Derived declares `static constexpr int kId` (distinct from every other command's id) and a
/// `bool sameTarget(const Derived&) const` that this base can reach (public, or a friend).
template <class Derived, class Value>
class ValueEditCommand : public QUndoCommand {
public:
    int id() const override { return Derived::kId; }

    bool mergeWith(const QUndoCommand* other) override {
        if (other->id() != id())
            return false;
        const Derived& next = static_cast<const Derived&>(*other);
        const ValueEditCommand& nextEdit = next;
        if (m_mergeKey == 0 || nextEdit.m_mergeKey != m_mergeKey ||
            !static_cast<const Derived&>(*this).sameTarget(next))
            return false;
        m_new = nextEdit.m_new;
        setObsolete(m_new == m_old);
        return true;
    }

protected:
    ValueEditCommand(Value oldValue, Value newValue, int mergeKey, QUndoCommand* parent)
        : QUndoCommand(parent), m_old(std::move(oldValue)), m_new(std::move(newValue)),
          m_mergeKey(mergeKey) {}

    Value m_old;
    Value m_new;
    int m_mergeKey; ///< 0: never merges (a typed value, a single click)
};

} // namespace velvet::ui
