// Stands in for the generated include of the same name, which replaces it in the programs built
// with LIGHTING_INLINE_POST (render/inline_post.h; generated includes are looked up before this
// folder): lighting.frag includes it unconditionally (an include under a false #if would shift
// its error lines), so the programs without the display step include this empty file. Not named
// post_*: those are post effects.
