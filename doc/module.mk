# doc: the user guide, command reference and benchmark record.
dist_doc_DATA += README.md LICENSE doc/commands.md doc/scene.md doc/rt.md doc/BENCHMARKS.md
