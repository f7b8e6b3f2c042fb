;;; bodyls.el --- Choreonoid Body files: a major mode and bodyls through eglot  -*- lexical-binding: t -*-

;; Load it from your init file:
;;
;;   (load "/path/to/bodyfmt/editors/emacs/bodyls.el")
;;
;; *.body files then open in `body-mode' (YAML-like: `#' comments, keys highlighted, two-space
;; indents), and eglot starts bodyls, the Body-format language server, for them; C-c C-v
;; (`bodyls-open-viewer') opens the model in bodyview beside the editor.  Set
;; `bodyls-program' when bodyls is not on `exec-path'.  Needs eglot (built into Emacs 29; Debian's
;; elpa-eglot for Emacs 28).

;;; Code:

(eval-and-compile
  (unless (require 'eglot nil t)
    ;; An eglot installed as a package (ELPA, Debian's elpa-eglot) is on the load path only
    ;; once the package system is initialised, which `emacs --batch' and some init files never do.
    (package-initialize)
    (require 'eglot)))

(defgroup bodyls nil
  "Choreonoid Body files with the bodyls language server."
  :group 'languages)

(defcustom bodyls-program "bodyls"
  "The bodyls executable: a name on `exec-path' or an absolute file name."
  :type 'string)

(defcustom bodyls-start-eglot t
  "Whether opening a Body file starts eglot (bodyls) for it."
  :type 'boolean)

(defvar body-mode-syntax-table
  (let ((table (make-syntax-table)))
    (modify-syntax-entry ?# "<" table)
    (modify-syntax-entry ?\n ">" table)
    (modify-syntax-entry ?_ "_" table)
    (modify-syntax-entry ?\' "\"" table)
    table)
  "Syntax table of `body-mode': YAML's comments and quotes.")

(defvar body-mode-font-lock-keywords
  '(("^[ \t]*\\(?:-[ \t]+\\)?\\([A-Za-z_][A-Za-z0-9_]*\\)[ \t]*:" 1 font-lock-variable-name-face)
    ("[{,][ \t]*\\([A-Za-z_][A-Za-z0-9_]*\\)[ \t]*:" 1 font-lock-variable-name-face)
    ("[&*][A-Za-z0-9_.-]+" . font-lock-constant-face)
    ("\\_<\\(true\\|false\\|null\\)\\_>" . font-lock-keyword-face))
  "Keys, anchors and aliases, and YAML's constants.")

;;;###autoload
(define-derived-mode body-mode prog-mode "Body"
  "Major mode for Choreonoid Body files (YAML)."
  (setq-local comment-start "# ")
  (setq-local comment-start-skip "#+[ \t]*")
  (setq-local indent-tabs-mode nil)
  (setq-local tab-width 2)
  (setq-local font-lock-defaults '(body-mode-font-lock-keywords)))

;;;###autoload
(add-to-list 'auto-mode-alist '("\\.body\\'" . body-mode))

(add-to-list 'eglot-server-programs
             `(body-mode . ,(lambda (&optional _interactive) (list bodyls-program))))

(defun bodyls-open-viewer ()
  "Open the current model in bodyview beside the editor.
bodyls serves the model's page with `bodyview --serve' (it reloads
on save) and answers with its address, which is opened with
`browse-url' and returned."
  (interactive)
  (let* ((server (or (eglot-current-server) (user-error "bodyls is not running for this buffer")))
         (result (eglot-execute-command server "bodyls.openViewer"
                                        (vector (eglot--path-to-uri (buffer-file-name)))))
         (url (plist-get result :url)))
    (when (and url (called-interactively-p 'interactive))
      (browse-url url))
    url))

(define-key body-mode-map (kbd "C-c C-v") #'bodyls-open-viewer)

(defun bodyls--maybe-start ()
  (when bodyls-start-eglot (eglot-ensure)))

(add-hook 'body-mode-hook #'bodyls--maybe-start)

(provide 'bodyls)
;;; bodyls.el ends here
