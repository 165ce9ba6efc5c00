#pragma once
/// @file hdri_thumbnail.h
/// Small display-referred pictures of HDR environments for the HDRI chooser (issue 17, item 15).

#include <QIcon>
#include <QSize>
#include <QString>

namespace velvet::ui {

/// The chooser's thumbnail size: 2:1, as an equirectangular panorama is.
inline constexpr QSize kHdriThumbnailSize{48, 24};

/// A thumbnail of the HDR image @p file (EXR, HDR, …): box-filtered down to @p size, exposed for
/// its log-average luminance and tone mapped (Reinhard et al. 2002), sRGB encoded. Cached per
/// file, modification time and size, so refilling a combo box costs nothing. A null icon when
/// the file cannot be read.
QIcon hdriThumbnail(const QString& file, QSize size = kHdriThumbnailSize);

} // namespace velvet::ui
