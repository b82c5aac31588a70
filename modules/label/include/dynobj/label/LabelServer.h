// SPDX-License-Identifier: BSD-3-Clause
// dynobj-label's HTTP side: serves the page (share/dynobj/label/) and a small JSON API over one
// LabelEditor on 127.0.0.1 only (cpp-httplib, Debian's libcpp-httplib-dev), and saves the session
// every few seconds when it changed (autosave) and on request. The API (all JSON unless noted):
//   GET  /api/info                      input, size, counts, objects, save state
//   GET  /api/sweep?k=N                 labels of sweep N (objects: id, state, pixels), reviewed
//   GET  /api/sweep-data?k=N            binary: intensity u8[H*W], ground u8[H*W], then float32
//                                       x[H*W], y[H*W], z[H*W] (little-endian)
//   POST /api/grow      {k,row,col,id,distance,max_extent}   -> {pixels}
//   POST /api/object    {k,id,pixels,state}  (id <= 0: a new object) -> {id}
//   POST /api/object-info {id,class,moving}
//   POST /api/propagate {k,id,steps}     -> {steps: [{to,found,kept,pixels,ego_motion}]}
//   POST /api/review    {k,reviewed,propagate}
//   POST /api/save                       -> {files} (500 {error} when the save failed)
// Errors: 400 {error} for a request the session refuses, 500 {error} for anything else.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "dynobj/label/LabelEditor.h"

namespace dynobj::label {

struct ServerOptions {
  int port = 8080;          ///< 0 = any free port
  std::string page_dir;     ///< share/dynobj/label
  std::string output;       ///< base name of the saved files (LabelEditor::save)
  std::string rawlog;       ///< recorded in the session file
  double autosave_s = 2.0;  ///< save this often when something changed (0 = only on request)
};

class LabelServer {
 public:
  /// Checks the page folder (throws LabelError when index.html is missing).
  LabelServer(LabelEditor& session, ServerOptions opts);
  ~LabelServer();
  LabelServer(const LabelServer&) = delete;
  LabelServer& operator=(const LabelServer&) = delete;

  /// Binds 127.0.0.1:port; returns the port. Throws LabelError naming it when it is in use.
  int bind();
  /// Serves until stop() (from another thread); autosaves meanwhile.
  void run();
  void stop();
  /// Saves now if anything changed since the last save (or always, with `force`); returns false
  /// and fills `error` when the save failed (the session keeps its state).
  bool save(std::string& error, bool force = false);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dynobj::label
