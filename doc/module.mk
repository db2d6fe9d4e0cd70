# doc: the user guide, command reference and benchmark record.
dist_doc_DATA += README.md LICENSE
dist_doc_DATA += doc/parallel.md doc/BENCHMARKS.md
