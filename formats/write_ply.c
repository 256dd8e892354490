/* placeholder: being written */
typedef int oit_placeholder_write_ply;
