/* placeholder: being written */
typedef int oit_placeholder_read_mesh;
