// Stands in for the generated include of the same name, which replaces it in the programs built
// with LIGHTING_INLINE_POST (render/inline_post.h; generated includes are looked up before this
// folder): the shader preprocessor expands every #include, even under a false #if, so the
// programs without the display step include this empty file.
