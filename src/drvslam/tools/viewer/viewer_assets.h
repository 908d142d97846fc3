// The viewer page, embedded at build time (web/ bundled by esbuild, then drvslam_embed_assets):
// the binary serves it and inlines it into reports without any file or network at run time.
#pragma once

#include <string_view>

namespace drvslam {

// The page's script: three.js and web/src/*.js in one minified IIFE.
std::string_view ViewerScript();
// web/index.html: the page, with the comment <!--DRVSLAM_SCRIPT--> where the script goes.
std::string_view ViewerPage();

}  // namespace drvslam
