# doc: the user guide, command reference and benchmark record.
dist_doc_DATA += README.md LICENSE doc/commands.md doc/scene.md doc/snapshot.md doc/rt.md
dist_doc_DATA += doc/ARCHITECTURE.md doc/vmd-behaviour.md
dist_doc_DATA += doc/parallel.md doc/BENCHMARKS.md doc/movies.md doc/live.md doc/ocl.md
dist_doc_DATA += doc/SECURITY.md doc/pbctools.md doc/exectool.md doc/live-page.png
dist_doc_DATA += doc/vmdmovie.md doc/viewchangerender.md
dist_doc_DATA += doc/js-format.md
dist_doc_DATA += doc/topotools.md
dist_doc_DATA += doc/python.md doc/analysis.ipynb
# The manual page, molscope(1): `man molscope` after `make install`.
dist_man_MANS = doc/molscope.1
