-- urdf_validate server in Neovim 0.11 and later (vim.lsp.config and vim.lsp.enable arrived in 0.11; for
-- 0.7 to 0.10: urdf_validate.lua). Save as ~/.config/nvim/lua/urdf_validate.lua and add
-- `require("urdf_validate")` to init.lua (or paste it there). The test suite runs this file as it is in
-- Neovim 0.11.4.
--
-- Neovim 0.11's defaults then apply to the robot files: K hover, gra code actions (fixes, "fix all safe",
-- suppressions), grr references, gO the kinematic tree, [d and ]d the previous and next finding, <C-w>d the
-- finding under the cursor, <C-x><C-o> completion, <C-]> go to definition. The server has no rename.

-- Neovim does not know these extensions: edit them as XML (xacro covers .urdf.xacro).
vim.filetype.add({ extension = { urdf = "xml", xacro = "xml", sdf = "xml", world = "xml" } })

vim.lsp.config("urdf_validate", {
  -- Options after "server" apply to every file, e.g. "--package-path", vim.fn.expand("~/ros2_ws/src").
  cmd = { "urdf_validate", "server" },
  filetypes = { "xml" },
  -- Only the files the server analyses (it ignores other XML), one server per workspace: the nearest
  -- folder above the file holding .git, else package.xml, else the file's own folder.
  root_dir = function(bufnr, on_dir)
    local path = vim.api.nvim_buf_get_name(bufnr)
    local name = path:lower()
    for _, extension in ipairs({ ".urdf", ".xacro", ".sdf", ".world" }) do
      if vim.endswith(name, extension) then
        on_dir(vim.fs.root(bufnr, { ".git", "package.xml" }) or vim.fs.dirname(path))
        return
      end
    end
  end,
})
vim.lsp.enable("urdf_validate")

vim.api.nvim_create_autocmd("LspAttach", {
  group = vim.api.nvim_create_augroup("urdf_validate", { clear = true }),
  callback = function(args)
    local client = vim.lsp.get_client_by_id(args.data.client_id)
    if client and client.name == "urdf_validate" then
      vim.keymap.set("n", "gd", vim.lsp.buf.definition, {
        buffer = args.buf,
        desc = "urdf_validate: go to definition",
      })
    end
  end,
})
