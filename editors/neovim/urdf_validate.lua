-- urdf_validate server in Neovim 0.7 to 0.10 (Neovim 0.11 and later: urdf_validate-0.11.lua).
-- Save as ~/.config/nvim/lua/urdf_validate.lua and add `require("urdf_validate")` to init.lua (or paste
-- it there). The test suite runs this file as it is in Debian bookworm's Neovim 0.7.2.

-- The server's command; options after "server" apply to every file, e.g.
-- { "urdf_validate", "server", "--package-path", vim.fn.expand("~/ros2_ws/src") }.
local cmd = { "urdf_validate", "server" }
-- The files the server analyses (it ignores other XML).
local extensions = { ".urdf", ".xacro", ".sdf", ".world" }
-- One server per workspace: the nearest folder above the file holding .git, else package.xml, else the
-- file's own folder.
local root_markers = { ".git", "package.xml" }

local group = vim.api.nvim_create_augroup("urdf_validate", { clear = true })

-- Neovim does not know these extensions: edit them as XML (*.xacro covers *.urdf.xacro).
vim.api.nvim_create_autocmd({ "BufRead", "BufNewFile" }, {
  group = group,
  pattern = { "*.urdf", "*.xacro", "*.sdf", "*.world" },
  command = "setlocal filetype=xml",
})

local function is_robot_file(path)
  local name = path:lower()
  for _, extension in ipairs(extensions) do
    if name:sub(-#extension) == extension then
      return true
    end
  end
  return false
end

local function root_of(path)
  local dir = vim.fn.fnamemodify(path, ":p:h")
  for _, marker in ipairs(root_markers) do
    -- .git is a folder, or a file in a git worktree or submodule.
    local found = vim.fn.finddir(marker, dir .. ";")
    if found == "" then
      found = vim.fn.findfile(marker, dir .. ";")
    end
    if found ~= "" then
      return vim.fn.fnamemodify(vim.fn.fnamemodify(found, ":p"):gsub("/$", ""), ":h")
    end
  end
  return dir
end

local function on_attach(_, bufnr)
  -- <C-x><C-o> completes link, joint, material and xacro names and rule codes.
  vim.bo[bufnr].omnifunc = "v:lua.vim.lsp.omnifunc"
  local function map(keys, action, desc)
    vim.keymap.set("n", keys, action, { buffer = bufnr, desc = desc })
  end
  map("K", vim.lsp.buf.hover, "urdf_validate: hover (mass, gravity torque, effort margin)")
  map("gd", vim.lsp.buf.definition, "urdf_validate: go to definition")
  map("gr", vim.lsp.buf.references, "urdf_validate: references")
  map("gO", vim.lsp.buf.document_symbol, "urdf_validate: kinematic tree")
  map("<leader>ca", vim.lsp.buf.code_action, "urdf_validate: fixes and suppressions")
  map("[d", vim.diagnostic.goto_prev, "previous finding")
  map("]d", vim.diagnostic.goto_next, "next finding")
  map("<leader>e", vim.diagnostic.open_float, "the finding under the cursor")
  -- The server has no rename.
end

local clients = {} -- workspace root -> client id

vim.api.nvim_create_autocmd("FileType", {
  group = group,
  pattern = "xml",
  callback = function(args)
    local path = vim.api.nvim_buf_get_name(args.buf)
    if not is_robot_file(path) then
      return
    end
    local root = root_of(path)
    local id = clients[root]
    if not (id and vim.lsp.get_client_by_id(id)) then
      id = vim.lsp.start_client({
        name = "urdf_validate",
        cmd = cmd,
        root_dir = root,
        on_attach = on_attach,
      })
      clients[root] = id
    end
    if id then
      vim.lsp.buf_attach_client(args.buf, id)
    end
  end,
})
